// SPDX-License-Identifier: Apache-2.0
// Config controls against libcamera: names and types through its registry, ranges against a camera's
// ControlInfoMap (built here as a pipeline handler builds one), every problem in the config's file:line shape.
#include <cmath>

#include <gtest/gtest.h>
#include <libcamera/control_ids.h>

#include "drivers/libcamera/libcamera_controls.h"

namespace overlayd {
namespace {

namespace c = libcamera::controls;

libcamera::ControlInfoMap cameraControls()
{
    return libcamera::ControlInfoMap(
        {
            {&c::Brightness, libcamera::ControlInfo(-1.0f, 1.0f)},
            {&c::AeEnable, libcamera::ControlInfo(false, true)},
            {&c::ExposureTime, libcamera::ControlInfo(int32_t(100), int32_t(10000))},
        },
        c::controls);
}

ControlSetting setting(const std::string &name, std::variant<bool, int64_t, double> value)
{
    return {name, value, "cam.toml:7:14: source.libcamera.controls." + name};
}

TEST(Controls, RegistryKnowsNamesAndTypes)
{
    EXPECT_EQ(libcameraControlKind("AeEnable"), ControlValueKind::Bool);
    EXPECT_EQ(libcameraControlKind("ExposureTime"), ControlValueKind::Integer);
    EXPECT_EQ(libcameraControlKind("Brightness"), ControlValueKind::Float);
    EXPECT_EQ(libcameraControlKind("Brightnes"), std::nullopt);
    const auto names = libcameraControlNames();
    EXPECT_NE(std::find(names.begin(), names.end(), "AnalogueGain"), names.end());
}

TEST(Controls, ValuesInsideTheCamerasRangesAreSet)
{
    // The list keeps a pointer to the camera's map, as it does to a real camera's.
    const libcamera::ControlInfoMap camera = cameraControls();
    auto list =
        buildControls({setting("Brightness", 0.25), setting("AeEnable", false), setting("ExposureTime", 5000)}, camera);
    ASSERT_TRUE(list.ok()) << list.error().message;
    EXPECT_FLOAT_EQ(list->get(c::Brightness).value_or(-9.0f), 0.25f);
    EXPECT_EQ(list->get(c::AeEnable), std::optional<bool>(false));
    EXPECT_EQ(list->get(c::ExposureTime), std::optional<int32_t>(5000));
}

TEST(Controls, EveryProblemNamesFileLineAndKey)
{
    auto list = buildControls({setting("Brightness", 1.5), setting("ExposureTime", 50), setting("Contrast", 1.0),
                               setting("AeEnable", int64_t(1))},
                              cameraControls());
    ASSERT_FALSE(list.ok());
    EXPECT_EQ(list.error().code, ErrorCode::ConfigError);
    const std::string &m = list.error().message;
    EXPECT_NE(m.find("cam.toml:7:14: source.libcamera.controls.Brightness: 1.5"), std::string::npos) << m;
    EXPECT_NE(m.find("outside -1"), std::string::npos) << m;
    EXPECT_NE(m.find("source.libcamera.controls.ExposureTime: 50 is outside 100..10000"), std::string::npos) << m;
    EXPECT_NE(m.find("source.libcamera.controls.Contrast: this camera has no control Contrast"), std::string::npos)
        << m;
    EXPECT_NE(m.find("source.libcamera.controls.AeEnable: "), std::string::npos) << m;
    EXPECT_EQ(std::count(m.begin(), m.end(), '\n'), 3) << m;
}

TEST(Controls, IntegersBeyondTheControlsTypeAreRefused)
{
    auto list = buildControls({setting("ExposureTime", int64_t(1) << 40)}, cameraControls());
    ASSERT_FALSE(list.ok());
    EXPECT_NE(list.error().message.find("ExposureTime"), std::string::npos);
}

// What no camera could take, known from libcamera's table alone (check-config asks this; buildControls refuses the
// same values with the same words).
TEST(Controls, ValuesNoCameraCouldTakeAreRefusedWithoutACamera)
{
    EXPECT_EQ(libcameraControlProblem(setting("Brightness", 0.5)), "");
    EXPECT_EQ(libcameraControlProblem(setting("ExposureTime", int64_t(INT32_MAX))), "");
    EXPECT_NE(libcameraControlProblem(setting("Brightness", std::nan(""))).find("not a number"), std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("Brightness", 1e39)).find("float"), std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("Brightness", -HUGE_VAL)).find("float"), std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("ExposureTime", int64_t(INT32_MAX) + 1)).find("32-bit"),
              std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("ColourGains", 1.5)).find("array"), std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("FrameDurationLimits", int64_t(33333))).find("array"), std::string::npos);
    EXPECT_NE(libcameraControlProblem(setting("Brightnes", 0.5)).find("unknown"), std::string::npos);
    const auto list = buildControls({setting("Brightness", std::nan(""))}, cameraControls());
    ASSERT_FALSE(list.ok());
    EXPECT_NE(list.error().message.find("Brightness: not a number"), std::string::npos) << list.error().message;
}

} // namespace
} // namespace overlayd
