// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as a calibration file. Each input is read twice: named .yaml (OpenCV YAML when it
// starts with "%YAML:", OpenCV XML with "<?xml", ROS camera_info YAML otherwise) and named .xml (always OpenCV's
// reader). The loaders must return a calibration or an error, never crash, hang, leak or allocate what a declared
// matrix size asks for (run under ASan + UBSan in CI, with -rss_limit_mb).
#include <cstddef>
#include <cstdint>
#include <string>

#include "config/calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const std::string text(reinterpret_cast<const char *>(data), size);
    (void)overlayd::loadCalibrationText("fuzz.yaml", text);
    (void)overlayd::loadCalibrationText("fuzz.xml", text);
    return 0;
}
