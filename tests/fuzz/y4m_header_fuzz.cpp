// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as a Y4M stream header line (what a replay source reads first from a file).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "drivers/files/y4m_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)overlayd::parseY4mHeader(std::string_view(reinterpret_cast<const char *>(data), size), "fuzz.y4m");
    return 0;
}
