// SPDX-License-Identifier: Apache-2.0
// [[gpio.input]] / [[gpio.output]]: every key read; the shape checked without hardware (what check-config can
// know), each problem at its file:line:key: unknown layers, lines named twice, missing chips and lines, limits.
#include <gtest/gtest.h>

#include "config_test_util.h"
#include "gpio/line_provider.h"

namespace overlayd::test {
namespace {

const std::string kScene = R"([[annotation]]
name = "guides"
type = "axes"
style = { layer = "guides" }
[[annotation]]
name = "logo"
type = "axes"
style = { layer = "logo" }
)";

// The shape checks run where [gpio] is available: a build without libgpiod refuses the table whole (below).
class GpioConfig : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!haveLibgpiod())
            GTEST_SKIP() << "built without libgpiod (OVERLAYD_GPIOD=OFF): [gpio] is refused whole";
    }
};

TEST(GpioConfigWithoutLibgpiod, GpioIsRefusedAtItsKey)
{
    if (haveLibgpiod())
        GTEST_SKIP() << "built with libgpiod";
    const auto problems = loadInvalid(kScene + "[[gpio.input]]\nchip = \"gpiochip0\"\nline = 3\nshow = [\"guides\"]\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "gpio");
    EXPECT_NE(problems[0].message.find("OVERLAYD_GPIOD"), std::string::npos) << problems[0].message;
}

TEST_F(GpioConfig, EveryKeyIsRead)
{
    const DaemonConfig config = loadValid(kScene + R"(
[[gpio.input]]
name = "reverse"
chip = "gpiochip0"
line = 17
active_low = true
bias = "pull-up"
debounce_ms = 30
show_layers = ["guides"]
hide_layers = ["logo"]

[[gpio.output]]
name = "status-led"
chip = "/dev/gpiochip1"
line = "STATUS"
signal = "frame-toggle"
active_low = true
)");
    ASSERT_EQ(config.gpio.inputs.size(), 1u);
    const GpioInputOptions &in = config.gpio.inputs[0];
    EXPECT_EQ(in.name, "reverse");
    EXPECT_EQ(in.line, (LineAddress{"gpiochip0", "", 17}));
    EXPECT_TRUE(in.activeLow);
    EXPECT_EQ(in.bias, Bias::PullUp);
    EXPECT_EQ(in.debounceMs, 30u);
    EXPECT_EQ(in.showLayers, std::vector<std::string>{"guides"});
    EXPECT_EQ(in.hideLayers, std::vector<std::string>{"logo"});
    ASSERT_EQ(config.gpio.outputs.size(), 1u);
    const OutputOptions &out = config.gpio.outputs[0];
    EXPECT_EQ(out.line, (LineAddress{"/dev/gpiochip1", "STATUS", 0}));
    EXPECT_EQ(out.signal, OutputSignal::FrameToggle);
    EXPECT_TRUE(out.activeLow);
}

TEST_F(GpioConfig, DefaultsAreTheDocumentedOnes)
{
    const DaemonConfig config =
        loadValid(kScene + "[[gpio.input]]\nchip = \"c\"\nline = 1\nshow_layers = [\"guides\"]\n"
                           "[[gpio.output]]\nchip = \"c\"\nline = 2\n");
    const GpioInputOptions &in = config.gpio.inputs.at(0);
    EXPECT_EQ(in.name, "gpio.input[0]");
    EXPECT_FALSE(in.activeLow);
    EXPECT_EQ(in.bias, Bias::AsIs);
    EXPECT_EQ(in.debounceMs, 20u);
    EXPECT_EQ(config.gpio.outputs.at(0).signal, OutputSignal::Streaming);
}

TEST_F(GpioConfig, AnUnknownLayerIsRefusedAtItsKeyWithASuggestion)
{
    const auto problems = loadInvalid(kScene + "[[gpio.input]]\nchip = \"c\"\nline = 1\nshow_layers = [\"guide\"]\n");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_EQ(problems[0].key, "gpio.input[0].show_layers");
    EXPECT_EQ(problems[0].line, 12u);
    EXPECT_NE(problems[0].message.find("no annotation draws in layer 'guide'"), std::string::npos);
    EXPECT_NE(problems[0].message.find("did you mean 'guides'?"), std::string::npos);
}

TEST_F(GpioConfig, TwoUsesOfOneLineAreRefusedWhereTheSecondIsWritten)
{
    const auto problems = loadInvalid(kScene + R"(
[[gpio.input]]
name = "reverse"
chip = "gpiochip0"
line = "REV"
show_layers = ["guides"]
[[gpio.output]]
name = "led"
chip = "gpiochip0"
line = "REV"
)");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_EQ(problems[0].key, "gpio.output[0].line");
    EXPECT_EQ(problems[0].line, 18u);
    EXPECT_NE(problems[0].message.find("gpiochip0 line 'REV' is already used by input 'reverse'"), std::string::npos)
        << problems[0].message;
}

TEST_F(GpioConfig, BadShapesAreEachNamed)
{
    const auto problems = loadInvalid(kScene + R"(
[[gpio.input]]
line = -1
bias = "pull-sideways"
debounce_ms = 20000
show_layers = "guides"
[[gpio.output]]
chip = "c"
line = 3
signal = "streamin"
colour = "red"
)");
    const std::string all = test::formatProblems(problems);
    for (const char *expected :
         {"gpio.input[0].chip: missing", "gpio.input[0].line:", "gpio.input[0].bias:", "gpio.input[0].debounce_ms:",
          "gpio.input[0].show_layers: expected an array of strings",
          "gpio.output[0].signal:", "gpio.output[0].colour:"})
        EXPECT_NE(all.find(expected), std::string::npos) << expected << " in\n" << all;
}

TEST_F(GpioConfig, AnInputThatSwitchesNothingIsRefused)
{
    const auto problems = loadInvalid(kScene + "[[gpio.input]]\nchip = \"c\"\nline = 1\n");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_NE(problems[0].message.find("needs show_layers or hide_layers"), std::string::npos);
}

// libgpiod v1 opens "0", "gpiochip0" and "/dev/gpiochip0" as one chip: a line under two of them is one line.
TEST_F(GpioConfig, OneLineUnderTwoSpellingsOfItsChipIsUsedTwice)
{
    for (const char *other : {"/dev/gpiochip0", "0", "00"}) {
        const auto problems = loadInvalid(kScene +
                                          "[[gpio.input]]\nchip = \"gpiochip0\"\nline = 5\n"
                                          "show_layers = [\"guides\"]\n[[gpio.output]]\nchip = \"" +
                                          other + "\"\nline = 5\n");
        ASSERT_EQ(problems.size(), 1u) << other << "\n" << test::formatProblems(problems);
        EXPECT_EQ(problems[0].key, "gpio.output[0].line") << other;
    }
    LineAddress byName{"gpiochip0", "", 5}, otherChip{"/dev/gpiochip1", "", 5}, label{"pinctrl", "", 5};
    EXPECT_FALSE(byName.sameLine(otherChip));
    EXPECT_FALSE(byName.sameLine(label)); // a label is known only on the machine
    EXPECT_FALSE(byName.sameLine({"gpiochip0", "", 6}));
}

// Shown only while active and hidden while active: never seen. An empty list switches nothing.
TEST_F(GpioConfig, AnInputCannotShowAndHideOneLayerOrSwitchAnEmptyList)
{
    auto problems = loadInvalid(kScene + "[[gpio.input]]\nchip = \"c\"\nline = 1\nshow_layers = [\"guides\", "
                                         "\"logo\"]\nhide_layers = [\"logo\"]\n");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_EQ(problems[0].key, "gpio.input[0].hide_layers");
    EXPECT_NE(problems[0].message.find("layer 'logo' is in show_layers too"), std::string::npos);
    problems = loadInvalid(kScene + "[[gpio.input]]\nchip = \"c\"\nline = 1\nhide_layers = []\n");
    ASSERT_EQ(problems.size(), 1u) << test::formatProblems(problems);
    EXPECT_EQ(problems[0].key, "gpio.input[0].hide_layers");
    EXPECT_NE(problems[0].message.find("would switch nothing"), std::string::npos);
}

TEST_F(GpioConfig, InputsAreLimited)
{
    std::string text = kScene;
    for (size_t i = 0; i <= kMaxInputs; ++i)
        text += "[[gpio.input]]\nchip = \"c\"\nline = " + std::to_string(i) + "\nshow_layers = [\"guides\"]\n";
    const auto problems = loadInvalid(text);
    EXPECT_NE(
        test::formatProblems(problems).find("gpio.input[32]: too many [[gpio.input]] tables: at most 32 (got 33)"),
        std::string::npos)
        << test::formatProblems(problems);
}

} // namespace
} // namespace overlayd::test
