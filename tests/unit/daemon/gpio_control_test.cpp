// SPDX-License-Identifier: Apache-2.0
// GpioControl against simulated lines: start state read, active-low, debounce, the show/hide precedence through
// SceneControl, outputs across the daemon's states, reloads that keep unchanged lines, busy and lost lines.
#include "control/gpio_control.h"

#include <gtest/gtest.h>

#include "fake_gpio.h"
#include "fakes.h"

namespace overlayd {
namespace {

using State = GpioControl::State;

OverlayScene layeredScene()
{
    OverlayScene scene;
    for (const char *layer : {"guides", "logo", "grid"}) {
        Annotation annotation{layer, "world", {}, GridShape{}};
        annotation.style.layer = layer;
        scene.annotations.push_back(annotation);
    }
    return scene;
}

GpioInputOptions input(const std::string &line, std::vector<std::string> show, std::vector<std::string> hide = {})
{
    GpioInputOptions o;
    o.name = line;
    o.line = {"chip0", line, 0};
    o.debounceMs = 0;
    o.showLayers = std::move(show);
    o.hideLayers = std::move(hide);
    return o;
}

OutputOptions output(const std::string &line, OutputSignal signal, bool activeLow = false)
{
    OutputOptions o;
    o.name = line;
    o.line = {"chip0", line, 0};
    o.signal = signal;
    o.activeLow = activeLow;
    return o;
}

struct GpioControlTest : ::testing::Test {
    std::vector<std::string> logged;
    Logger logger{[this](std::string_view line) { logged.emplace_back(line); }, true};
    test::FakeGpio lines;
    SceneControl scene{
        [](const OverlayScene &, const Camera &, const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
            return std::unique_ptr<OverlayRenderer>();
        }};
    GpioControl gpio{logger, scene};

    void SetUp() override
    {
        scene.load(layeredScene(), CameraSpec{});
        gpio.setProvider(lines.provider());
    }
    void start(const GpioOptions &options)
    {
        ASSERT_TRUE(gpio.configure(options).ok());
        gpio.applyLayers();
    }
    // An edge on a line without debounce: the loop would call onEdge when its fd is readable.
    void edge(size_t input, const std::string &line, bool physical)
    {
        lines.set("chip0", line, physical);
        gpio.onEdge(input);
    }
    bool logContains(const std::string &text) const
    {
        for (const std::string &line : logged)
            if (line.find(text) != std::string::npos)
                return true;
        return false;
    }
};

TEST_F(GpioControlTest, TheStateAtStartIsReadNotAssumed)
{
    lines.set("chip0", "reverse", true); // the car was started in reverse
    start({{input("reverse", {"guides"})}, {}});
    EXPECT_TRUE(gpio.inputActive(0));
    EXPECT_TRUE(scene.layerVisible("guides"));
    EXPECT_EQ(lines.line("chip0", "reverse").consumer, "overlayd");
}

TEST_F(GpioControlTest, ShowLayersAreVisibleOnlyWhileTheLineIsActive)
{
    start({{input("reverse", {"guides"})}, {}});
    EXPECT_FALSE(scene.layerVisible("guides"));
    EXPECT_TRUE(scene.layerVisible("logo")); // not named: left alone
    edge(0, "reverse", true);
    EXPECT_TRUE(scene.layerVisible("guides"));
    edge(0, "reverse", false);
    EXPECT_FALSE(scene.layerVisible("guides"));
}

TEST_F(GpioControlTest, ActiveLowInvertsThePhysicalLevel)
{
    GpioInputOptions reverse = input("reverse", {"guides"});
    reverse.activeLow = true;
    reverse.bias = Bias::PullUp;
    lines.set("chip0", "reverse", true); // pulled up: inactive
    start({{reverse}, {}});
    EXPECT_TRUE(lines.line("chip0", "reverse").activeLow);
    EXPECT_EQ(lines.line("chip0", "reverse").bias, Bias::PullUp);
    EXPECT_FALSE(scene.layerVisible("guides"));
    edge(0, "reverse", false); // the switch closes to ground
    EXPECT_TRUE(scene.layerVisible("guides"));
}

TEST_F(GpioControlTest, HidingWinsOverShowingAndShowingNeedsOneActiveInput)
{
    // reverse shows guides and hides logo; parking shows guides; menu hides guides.
    start({{input("reverse", {"guides"}, {"logo"}), input("parking", {"guides"}), input("menu", {}, {"guides"})}, {}});
    EXPECT_FALSE(scene.layerVisible("guides"));
    EXPECT_TRUE(scene.layerVisible("logo"));
    edge(1, "parking", true);
    EXPECT_TRUE(scene.layerVisible("guides"));
    edge(0, "reverse", true);
    EXPECT_TRUE(scene.layerVisible("guides"));
    EXPECT_FALSE(scene.layerVisible("logo"));
    edge(2, "menu", true); // an active hide beats two active shows
    EXPECT_FALSE(scene.layerVisible("guides"));
    edge(2, "menu", false);
    edge(1, "parking", false);
    EXPECT_TRUE(scene.layerVisible("guides")); // reverse alone still shows it
    edge(0, "reverse", false);
    EXPECT_FALSE(scene.layerVisible("guides"));
    EXPECT_TRUE(scene.layerVisible("logo"));
}

TEST_F(GpioControlTest, OnlyChangesAreAppliedSoOtherControlsKeepTheirChoiceBetweenEdges)
{
    start({{input("reverse", {"guides"}), input("parking", {"logo"})}, {}});
    ASSERT_TRUE(scene.apply(LayerChange{"guides", true}).ok()); // e.g. the HTTP API
    edge(1, "parking", true);                                   // another input's edge
    EXPECT_TRUE(scene.layerVisible("guides"));
}

TEST_F(GpioControlTest, BouncesShorterThanTheDebounceChangeNothing)
{
    GpioInputOptions reverse = input("reverse", {"guides"});
    reverse.debounceMs = 20;
    start({{reverse}, {}});
    edge(0, "reverse", true);
    EXPECT_FALSE(scene.layerVisible("guides")); // not before the line has been quiet for the debounce
    edge(0, "reverse", false);                  // the contact bounced back
    gpio.onDebounced(0);
    EXPECT_FALSE(scene.layerVisible("guides"));
    EXPECT_FALSE(gpio.inputActive(0));
    edge(0, "reverse", true);
    gpio.onDebounced(0);
    EXPECT_TRUE(scene.layerVisible("guides"));
}

TEST_F(GpioControlTest, TheDebounceTimerFiresThroughTheLoop)
{
    GpioInputOptions reverse = input("reverse", {"guides"});
    reverse.debounceMs = 5;
    start({{reverse}, {}});
    auto loop = EventLoop::create();
    ASSERT_TRUE(loop.ok());
    gpio.attachLoop(&*loop);
    lines.set("chip0", "reverse", true);
    ASSERT_TRUE(loop->runOnce(1000).ok()); // the edge: arms the debounce
    EXPECT_FALSE(scene.layerVisible("guides"));
    for (int i = 0; i < 20 && !scene.layerVisible("guides"); ++i)
        ASSERT_TRUE(loop->runOnce(1000).ok()); // the timerfd
    EXPECT_TRUE(scene.layerVisible("guides"));
    gpio.attachLoop(nullptr);
}

TEST_F(GpioControlTest, OutputsFollowTheDaemonsStateAndGoInactiveOnStop)
{
    start({{}, {output("led", OutputSignal::Streaming), output("nosig", OutputSignal::NoSignal, true)}});
    EXPECT_FALSE(lines.logical("chip0", "led"));
    EXPECT_FALSE(lines.logical("chip0", "nosig"));
    EXPECT_TRUE(lines.line("chip0", "nosig").physical); // active-low: inactive is high
    gpio.onState(State::Streaming);
    EXPECT_TRUE(lines.logical("chip0", "led"));
    gpio.onState(State::Waiting);
    EXPECT_FALSE(lines.logical("chip0", "led"));
    EXPECT_TRUE(lines.logical("chip0", "nosig"));
    EXPECT_FALSE(lines.line("chip0", "nosig").physical);
    gpio.onFrameDelivered(0); // frames again
    EXPECT_TRUE(lines.logical("chip0", "led"));
    EXPECT_FALSE(lines.logical("chip0", "nosig"));
    gpio.shutdown();
    EXPECT_FALSE(lines.logical("chip0", "led"));
    EXPECT_TRUE(lines.line("chip0", "led").consumer.empty());
}

TEST_F(GpioControlTest, FrameToggleFlipsOncePerFrameAndErrorFollowsSinkFailures)
{
    start({{}, {output("toggle", OutputSignal::FrameToggle), output("err", OutputSignal::Error)}});
    EXPECT_TRUE(gpio.wantsSinkFailures());
    std::vector<bool> levels;
    for (int frame = 0; frame < 4; ++frame) {
        gpio.onFrameDelivered(0);
        levels.push_back(lines.logical("chip0", "toggle"));
    }
    EXPECT_EQ(levels, (std::vector<bool>{true, false, true, false}));
    EXPECT_FALSE(lines.logical("chip0", "err"));
    gpio.onFrameDelivered(1); // a sink failed a write since the last frame
    EXPECT_TRUE(lines.logical("chip0", "err"));
    gpio.onFrameDelivered(1);
    EXPECT_FALSE(lines.logical("chip0", "err"));
}

TEST_F(GpioControlTest, ALineHeldByAnotherProcessIsRefusedNamingTheHolder)
{
    lines.line("chip0", "reverse").consumer = "gpiomon";
    const Status status = gpio.configure({{input("reverse", {"guides"})}, {}});
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("gpio input 'reverse'"), std::string::npos) << status.error().message;
    EXPECT_NE(status.error().message.find("'gpiomon'"), std::string::npos) << status.error().message;
}

TEST_F(GpioControlTest, AReloadKeepsUnchangedLinesAndReRequestsChangedOnes)
{
    start({{input("reverse", {"guides"}), input("parking", {"logo"})}, {output("led", OutputSignal::Streaming)}});
    GpioInputOptions parking = input("parking", {"logo"});
    parking.activeLow = true;
    ASSERT_TRUE(gpio.configure({{input("reverse", {"guides"}), parking}, {}}).ok());
    EXPECT_EQ(lines.line("chip0", "reverse").requests, 1u);   // kept
    EXPECT_EQ(lines.line("chip0", "parking").requests, 2u);   // changed: released and requested again
    EXPECT_TRUE(lines.line("chip0", "led").consumer.empty()); // removed: released
}

TEST_F(GpioControlTest, AFailedReloadKeepsEveryOldLine)
{
    start({{input("reverse", {"guides"})}, {output("led", OutputSignal::Streaming)}});
    lines.line("chip0", "busy").consumer = "someone";
    GpioInputOptions changed = input("reverse", {"guides"});
    changed.activeLow = true;
    const Status status =
        gpio.configure({{changed}, {output("led", OutputSignal::Streaming), output("busy", OutputSignal::Error)}});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(lines.line("chip0", "reverse").consumer, "overlayd");
    EXPECT_FALSE(lines.line("chip0", "reverse").activeLow); // as before the reload
    EXPECT_EQ(lines.line("chip0", "led").consumer, "overlayd");
    EXPECT_EQ(lines.line("chip0", "busy").consumer, "someone");
    EXPECT_EQ(gpio.describe(), "reverse 0, led 0");
}

TEST_F(GpioControlTest, ALostChipIsLoggedAndRetriedAndTheLineComesBack)
{
    start({{input("reverse", {"guides"})}, {}});
    lines.line("chip0", "reverse").lost = true;
    edge(0, "reverse", true);
    EXPECT_TRUE(logContains("gpio input 'reverse': No such device; requesting it again every 2 s"));
    EXPECT_EQ(gpio.describe(), "reverse lost");
    gpio.onRetry(); // still gone
    EXPECT_EQ(gpio.describe(), "reverse lost");
    lines.line("chip0", "reverse").lost = false;
    gpio.onRetry();
    EXPECT_EQ(gpio.describe(), "reverse 1");
    EXPECT_TRUE(scene.layerVisible("guides")); // the level read when it came back
    EXPECT_TRUE(logContains("gpio input 'reverse' is back"));
}

} // namespace
} // namespace overlayd
