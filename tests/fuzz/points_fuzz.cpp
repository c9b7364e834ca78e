// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as a solve-pose points file.
#include <cstddef>
#include <cstdint>
#include <string>

#include "alignment/points_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)overlayd::parsePoints(std::string(reinterpret_cast<const char *>(data), size), "fuzz.csv");
    return 0;
}
