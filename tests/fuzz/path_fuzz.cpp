// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as an [[input.path]] file (what another program writes while the daemon runs).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "inputs/point_list.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)overlayd::parsePointList(std::string_view(reinterpret_cast<const char *>(data), size), "fuzz.txt");
    return 0;
}
