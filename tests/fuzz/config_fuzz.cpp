// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as a config file. The loader must return a config or problems, never crash, hang or
// leak (run under ASan + UBSan in CI).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "config/daemon_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::vector<overlayd::ConfigProblem> problems;
    (void)overlayd::loadConfigText(std::string_view(reinterpret_cast<const char *>(data), size), "fuzz.toml",
                                   "/nonexistent", problems);
    return 0;
}
