// SPDX-License-Identifier: Apache-2.0
// Broken configs (tests/data/config/bad/) and a truncated Y4M: each run of the real binary exits non-zero with a
// message naming the problem, and nothing crashes (CI runs this under AddressSanitizer/UBSan too).
#include <ostream>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

struct BadConfig {
    const char *file;
    const char *named; // what the message must mention
};

// Names the case in test listings (CTest shows it) instead of its bytes.
void PrintTo(const BadConfig &value, std::ostream *out)
{
    *out << value.file;
}

class BadConfigs : public ::testing::TestWithParam<BadConfig>
{};

TEST_P(BadConfigs, CheckConfigRenderAndRunRefuseWithTheProblemNamed)
{
    const BadConfig bad = GetParam();
    const std::string config = badConfigPath(bad.file);
    const std::string dir = scratchDir(std::string("bad-") + bad.file);
    for (const std::string &args :
         {"check-config '" + config + "'", "render --config '" + config + "' --frames 2 --output out.y4m",
          "run --config '" + config + "' --frames 2"}) {
        SCOPED_TRACE(args);
        const RunResult run = runOverlayd(args, dir);
        EXPECT_FALSE(run.crashed) << run.all();
        EXPECT_EQ(run.exitStatus, 2) << run.all(); // the config error status
        EXPECT_NE(run.all().find(bad.named), std::string::npos) << run.all();
        EXPECT_NE(run.all().find(std::string(bad.file) + ":"), std::string::npos) << "no file:line in " << run.all();
    }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadConfigs,
    ::testing::Values(BadConfig{"syntax_error.toml", "syntax_error.toml:4"}, BadConfig{"wrong_type.toml", "width"},
                      BadConfig{"out_of_range.toml", "100000"}, BadConfig{"unknown_key.toml", "widht"},
                      BadConfig{"many_problems.toml", "log_level"}, BadConfig{"degenerate_up.toml", "up"},
                      BadConfig{"missing_calibration.toml", "no-such-calibration.yaml"},
                      BadConfig{"malformed_calibration.toml", "malformed_calibration.yaml"},
                      BadConfig{"gpio_line_twice.toml", "gpio.output[0].line: gpiochip0 line 'REVERSE_IN' is already "
                                                        "used by input 'reverse'"}),
    [](const auto &param) {
        std::string name = param.param.file;
        return name.substr(0, name.find('.'));
    });

TEST(TruncatedY4m, RenderStopsWithAnErrorNamingFileAndFrame)
{
    const RunResult run =
        runOverlayd("render --config '" + dataPath("replay_truncated.toml") + "' --frames 5 --output out.y4m",
                    scratchDir("truncated-render"));
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("truncated.y4m"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("frame 1"), std::string::npos) << run.err;
}

TEST(TruncatedY4m, RunStopsWithAnErrorToo)
{
    const RunResult run =
        runOverlayd("run --config '" + dataPath("replay_truncated.toml") + "'", scratchDir("truncated-run"));
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("frame 1"), std::string::npos) << run.err;
}

TEST(BadCommandLine, UnknownOutputExtensionIsRefused)
{
    const RunResult run =
        runOverlayd("render --config '" + dataPath("persp_yuyv_top_left.toml") + "' --frames 1 --output out.mp4",
                    scratchDir("bad-extension"));
    EXPECT_EQ(run.exitStatus, 1);
    EXPECT_NE(run.err.find("out.mp4"), std::string::npos) << run.err;
}

// A GPIO chip that is not there: check-config cannot know (chips exist only on the running machine), run refuses to
// start naming the chip, with the chips there are, and exits 1.
TEST(StartRefusal, AMissingGpioChipIsNamed)
{
    const std::string dir = scratchDir("gpio-missing-chip");
    writeFile(dir + "/gpio.toml", R"(
[source]
kind = "synthetic"
width = 64
height = 48
[[annotation]]
name = "guides"
type = "axes"
style = { layer = "guides" }
[[gpio.input]]
name = "reverse"
chip = "no-such-gpiochip"
line = 3
show_layers = ["guides"]
)");
    EXPECT_EQ(runOverlayd("check-config gpio.toml", dir).exitStatus, 0);
    const RunResult run = runOverlayd("run --config gpio.toml --frames 2", dir);
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    const bool named =
        run.all().find("gpio input 'reverse': GPIO chip 'no-such-gpiochip' not found") != std::string::npos ||
        run.all().find("built without libgpiod") != std::string::npos;
    EXPECT_TRUE(named) << run.all();
}

} // namespace
} // namespace overlayd::test
