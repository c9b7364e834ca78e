// SPDX-License-Identifier: Apache-2.0
// [source.libcamera]: every key read, control names and value types checked against libcamera's registry at load
// (what check-config can know without a camera), each problem at its file:line:key. A build without libcamera
// refuses the kind itself.
#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

const std::string kLibcameraSource = R"([source]
kind = "libcamera"
format = "NV12"
width = 1280
height = 720
[source.libcamera]
camera = "Sensor B"
role = "viewfinder"
buffers = 6
transform = "rot180"
controls = { AeEnable = true, Brightness = 0.1, ExposureTime = 20000 }
)";

TEST(LibcameraConfig, EveryKeyIsRead)
{
    if (!libcameraBuiltIn()) {
        const auto problems = loadInvalid(kLibcameraSource);
        ASSERT_EQ(problems.size(), 1u);
        EXPECT_EQ(problems[0].key, "source.kind");
        EXPECT_NE(problems[0].message.find("without libcamera"), std::string::npos);
        return;
    }
    const DaemonConfig config = loadValid(kLibcameraSource);
    const LibcameraOptions &o = config.source.libcamera;
    EXPECT_EQ(config.source.kind, SourceKind::Libcamera);
    EXPECT_EQ(o.camera, "Sensor B");
    EXPECT_EQ(o.role, StreamRole::Viewfinder);
    EXPECT_EQ(o.bufferCount, 6u);
    EXPECT_EQ(o.transform, ImageTransform::Rot180);
    ASSERT_EQ(o.controls.size(), 3u);
    for (const ControlSetting &c : o.controls) {
        if (c.name == "AeEnable")
            EXPECT_EQ(c.value, (std::variant<bool, int64_t, double>(true)));
        else if (c.name == "Brightness")
            EXPECT_EQ(c.value, (std::variant<bool, int64_t, double>(0.1)));
        else
            EXPECT_EQ(c.value, (std::variant<bool, int64_t, double>(int64_t(20000))));
        // Where the value sits, so that a range error found when the camera opens names the key.
        EXPECT_EQ(c.where.rfind("test.toml:11:", 0), 0u) << c.where;
        EXPECT_NE(c.where.find("source.libcamera.controls." + c.name), std::string::npos) << c.where;
    }
}

TEST(LibcameraConfig, UnknownControlsAndWrongTypesAreRefusedAtTheirKey)
{
    const auto problems = loadInvalid("[source]\nkind = \"libcamera\"\n[source.libcamera]\n"
                                      "controls = { Brightnes = 0.1, AeEnable = 1, ExposureTime = 1.5 }\n"
                                      "role = \"video-recording\"\nbuffers = 1\n");
    std::string all;
    for (const ConfigProblem &p : problems)
        all += p.format() + "\n";
    // Without libcamera there is no registry to check names against: the kind itself is refused.
    if (!libcameraBuiltIn()) {
        EXPECT_NE(all.find("source.kind: this overlayd was built without libcamera"), std::string::npos) << all;
        return;
    }
    ASSERT_EQ(problems.size(), 5u) << all;
    EXPECT_NE(all.find("test.toml:4:"), std::string::npos) << all;
    EXPECT_NE(all.find("source.libcamera.controls.Brightnes: unknown libcamera control (did you mean 'Brightness'?)"),
              std::string::npos)
        << all;
    EXPECT_NE(all.find("source.libcamera.controls.AeEnable: expected true or false, got an integer"), std::string::npos)
        << all;
    EXPECT_NE(all.find("source.libcamera.controls.ExposureTime: expected an integer"), std::string::npos) << all;
    EXPECT_NE(all.find("source.libcamera.role"), std::string::npos) << all;
    EXPECT_NE(all.find("source.libcamera.buffers"), std::string::npos) << all;
}

} // namespace
} // namespace overlayd::test
