// [[input.text]]: a slot some text shows, fed once, from a file whose folder exists; every refusal at its key.
#include <filesystem>

#include "config_test_util.h"

using namespace overlayd;
using overlayd::test::loadInvalid;
using overlayd::test::loadValid;

namespace {

const std::string kScene = R"(
[source]
kind = "synthetic"
width = 640
height = 480
[camera]
position = [0.0, -6.0, 3.0]
yaw = 90.0
[[annotation]]
type = "text"
text = "gear {slot:gear}, {slot:status}"
position = [10.0, 10.0]
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
