// SPDX-License-Identifier: Apache-2.0
// [[input.text]]: a slot some text shows, fed once, from a file whose folder exists; [[input.can]]: a signal layout
// that fits the 8 data bytes, an id within its width, a target the scene has, fed once; every refusal at its key.
#include <filesystem>

#include "config_test_util.h"

using namespace overlayd;
using overlayd::test::loadInvalid;
using overlayd::test::loadValid;

namespace {

const std::string kScene = test::kMinimalConfig + R"(
[[annotation]]
type = "text"
text = "gear {slot:gear}, {slot:status}"
position = [10.0, 10.0]
[[annotation]]
name = "guide lines"
type = "guide-lines"
steering_ratio = 15.0
stale_colour = "#808080"
[[annotation]]
name = "route"
type = "polyline"
points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
)";

} // namespace

TEST(InputConfig, ATextInputFeedsASlotFromAFileBesideTheConfig)
{
    const std::string base = std::filesystem::temp_directory_path().string();
    const DaemonConfig config = loadValid(kScene + "[[input.text]]\nslot = \"status\"\nfile = \"status.txt\"\n"
                                                   "max_bytes = 32\n",
                                          base);
    ASSERT_EQ(config.inputs.text.size(), 1u);
    EXPECT_EQ(config.inputs.text[0].slot, "status");
    EXPECT_EQ(config.inputs.text[0].file, base + "/status.txt");
    EXPECT_EQ(config.inputs.text[0].maxBytes, 32u);
    EXPECT_TRUE(loadValid(kScene).inputs.empty());
}

TEST(InputConfig, EveryRefusalIsAtItsKey)
{
    const auto problems = loadInvalid(kScene + R"(
[[input.text]]
slot = "stauts"
file = "/nonexistent-overlayd-folder/status.txt"
max_bytes = 257
[[input.text]]
slot = "gear"
file = "/tmp/gear.txt"
[[input.text]]
slot = "gear"
file = "/tmp/gear2.txt"
fiel = "x"
[[input.text]]
)");
    const std::string all = test::formatProblems(problems);
    const auto has = [&](const std::string &key, const std::string &words) {
        return test::hasProblem(problems, key, words);
    };
    EXPECT_TRUE(has("input.text[0].slot", "did you mean 'status'")) << all;
    EXPECT_TRUE(has("input.text[0].file", "does not exist")) << all;
    EXPECT_TRUE(has("input.text[0].max_bytes", "")) << all;
    EXPECT_TRUE(has("input.text[2].slot", "already fed")) << all;
    EXPECT_TRUE(has("input.text[2].fiel", "did you mean 'file'")) << all;
    EXPECT_TRUE(has("input.text[3].slot", "missing")) << all;
    EXPECT_TRUE(has("input.text[3].file", "missing")) << all;
}

TEST(InputConfig, ACanInputDrivesTheGuideLinesSteering)
{
    const DaemonConfig config = loadValid(kScene + R"(
[[input.can]]
name = "steering"
interface = "can0"
id = 0x025
start_bit = 7
length = 16
byte_order = "big-endian"
signed = true
scale = 0.1
offset = 0.5
unit = "deg"
min = -540.0
max = 540.0
timeout_ms = 250
step = 0.5
target = "guide lines.steering"
[[input.can]]
interface = "vcan0"
id = 0x18FEF100
id_extended = true
start_bit = 8
length = 16
scale = 0.00390625
unit = "km/h"
decimals = 0
stale_text = "?"
target = "slot:gear"
)");
    ASSERT_EQ(config.inputs.can.size(), 2u);
    const CanInputOptions &steering = config.inputs.can[0];
    EXPECT_EQ(steering.name, "steering");
    EXPECT_EQ(steering.interface, "can0");
    EXPECT_EQ(steering.id, (CanId{0x25, false}));
    EXPECT_EQ(steering.layout, (CanSignalLayout{7, 16, true, true, 0.1, 0.5}));
    EXPECT_EQ(steering.min, -540.0);
    EXPECT_EQ(steering.timeoutMs, 250);
    EXPECT_EQ(steering.step, 0.5);
    EXPECT_EQ(steering.target, (CanTarget{CanTarget::Kind::Steering, "guide lines"}));
    const CanInputOptions &speed = config.inputs.can[1];
    EXPECT_EQ(speed.name, "vcan0:419361024") << "a default name from interface and id";
    EXPECT_EQ(speed.id, (CanId{0x18FEF100, true}));
    EXPECT_FALSE(speed.layout.bigEndian);
    EXPECT_EQ(speed.decimals, 0);
    EXPECT_EQ(speed.staleText, "?");
    EXPECT_EQ(speed.target, (CanTarget{CanTarget::Kind::Slot, "gear"}));
    const auto &guide = std::get<GuideLinesShape>(config.scene.annotations[1].shape);
    EXPECT_EQ(guide.steeringRatio, 15.0);
    EXPECT_EQ(guide.staleColour, (Rgba{128, 128, 128, 255}));
}

TEST(InputConfig, EveryCanRefusalIsAtItsKey)
{
    const auto problems = loadInvalid(kScene + R"(
[[input.text]]
slot = "gear"
file = "/tmp/gear.txt"
[[input.can]]
interface = "can0/../x"
id = 0x800
start_bit = 60
length = 8
byte_order = "middle"
scale = 0
min = 5.0
max = 5.0
timeout_ms = 0
target = "guides.steering"
[[input.can]]
interface = "can0"
id = 0x20000000
id_extended = true
start_bit = 56
length = 2
byte_order = "big-endian"
target = "slot:gear"
[[input.can]]
id = 1
length = 8
target = "guide lines.yaw"
[[input.can]]
interface = "can1"
id = 2
start_bit = 0
length = 8
target = "guide lines.steering"
[[input.can]]
interface = "can1"
id = 3
start_bit = 0
length = 8
target = "guide lines.steering"
)");
    const std::string all = test::formatProblems(problems);
    const auto has = [&](const std::string &key, const std::string &words) {
        return test::hasProblem(problems, key, words);
    };
    EXPECT_TRUE(has("input.can[0].interface", "1..15 bytes")) << all;
    EXPECT_TRUE(has("input.can[0].id", "2047")) << all;
    EXPECT_TRUE(has("input.can[0].start_bit", "runs past the 8th data byte")) << all;
    EXPECT_TRUE(has("input.can[0].byte_order", "little-endian | big-endian")) << all;
    EXPECT_TRUE(has("input.can[0].scale", "scale of 0")) << all;
    EXPECT_TRUE(has("input.can[0].max", "greater than min")) << all;
    EXPECT_TRUE(has("input.can[0].timeout_ms", "")) << all;
    EXPECT_TRUE(has("input.can[0].target", "no guide-lines annotation is named 'guides'")) << all;
    EXPECT_TRUE(has("input.can[1].id", "536870911")) << all;
    EXPECT_TRUE(has("input.can[1].start_bit", "big-endian")) << all;
    EXPECT_TRUE(has("input.can[1].target", "already fed")) << all;
    EXPECT_TRUE(has("input.can[2].interface", "missing")) << all;
    EXPECT_TRUE(has("input.can[2].start_bit", "missing")) << all;
    EXPECT_TRUE(has("input.can[2].target", "expected")) << all;
    EXPECT_FALSE(has("input.can[3].target", "")) << all;
    EXPECT_TRUE(has("input.can[4].target", "already fed")) << all;
}

TEST(InputConfig, APathInputFeedsAPolylineFromAFile)
{
    const std::string base = std::filesystem::temp_directory_path().string();
    const DaemonConfig config =
        loadValid(kScene + "[[input.path]]\nannotation = \"route\"\nfile = \"route.txt\"\n", base);
    ASSERT_EQ(config.inputs.paths.size(), 1u);
    EXPECT_EQ(config.inputs.paths[0].annotation, "route");
    EXPECT_EQ(config.inputs.paths[0].file, base + "/route.txt");
    // A config named by a relative path in the working directory: its folder is "".
    EXPECT_EQ(
        loadValid(kScene + "[[input.path]]\nannotation = \"route\"\nfile = \"route.txt\"\n", "").inputs.paths[0].file,
        "route.txt");
}

TEST(InputConfig, EveryPathRefusalIsAtItsKey)
{
    const auto problems = loadInvalid(kScene + R"(
[[input.path]]
annotation = "rout"
file = "/nonexistent-overlayd-folder/route.txt"
[[input.path]]
annotation = "guide lines"
file = "/tmp/a.txt"
[[input.path]]
annotation = "route"
file = "/tmp/b.txt"
[[input.path]]
annotation = "route"
file = ""
[[input.path]]
)");
    const std::string all = test::formatProblems(problems);
    const auto has = [&](const std::string &key, const std::string &words) {
        return test::hasProblem(problems, key, words);
    };
    EXPECT_TRUE(has("input.path[0].annotation", "did you mean 'route'")) << all;
    EXPECT_TRUE(has("input.path[0].file", "does not exist")) << all;
    EXPECT_TRUE(has("input.path[1].annotation", "no polyline or markers annotation")) << all;
    EXPECT_FALSE(has("input.path[2].annotation", "")) << all;
    EXPECT_TRUE(has("input.path[3].annotation", "already fed")) << all;
    EXPECT_TRUE(has("input.path[3].file", "empty path")) << all;
    EXPECT_TRUE(has("input.path[4].annotation", "missing")) << all;
    EXPECT_TRUE(has("input.path[4].file", "missing")) << all;
}

TEST(InputConfig, TextFromOutsideHoldsNoControlCharacter)
{
    // TOML escapes make control characters toml++ lets through (it checks only the UTF-8): refused at their keys.
    const auto problems = loadInvalid(kScene + R"(
[[input.text]]
slot = "status"
file = "/tmp/sta\u0007tus.txt"
[[input.can]]
interface = "can0"
id = 1
start_bit = 0
length = 8
unit = "km\th"
stale_text = "n/a\u0085"
target = "slot:gear"
)");
    const std::string all = test::formatProblems(problems);
    EXPECT_TRUE(test::hasProblem(problems, "input.text[0].file", "a control character (U+0007) at byte 8")) << all;
    EXPECT_TRUE(test::hasProblem(problems, "input.can[0].unit", "a control character (U+0009) at byte 2")) << all;
    EXPECT_TRUE(test::hasProblem(problems, "input.can[0].stale_text", "a control character (U+0085) at byte 3")) << all;
}
