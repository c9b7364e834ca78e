// SPDX-License-Identifier: Apache-2.0
// CanInputs: a decoded CAN value drives its target through SceneControl only when it is valid and has moved by the
// input's step; a malformed frame changes nothing; out of range or silent for the timeout, the target shows
// "unknown" (the guide lines lose their wheel tracks, a slot shows the stale text) instead of the last value.
// Frames are handed in as the socket would deliver them (the socket itself runs against vcan in the VM tier).
#include "control/can_inputs.h"

#include <gtest/gtest.h>

#include "fakes.h"

namespace overlayd {
namespace {

using namespace std::chrono_literals;
using Clock = CanInputs::Clock;

OverlayScene reverseScene()
{
    OverlayScene scene;
    GuideLinesShape guide;
    guide.steeringRatio = 15.0;
    scene.annotations.push_back({"guide lines", "world", {}, guide});
    scene.annotations.push_back({"speed", "world", {}, ScreenTextShape{"{slot:speed}"}});
    return scene;
}

// The steering wheel: 16-bit signed big-endian at DBC start bit 7, 0.1 deg per bit, +-540 deg.
CanInputOptions steering()
{
    CanInputOptions options;
    options.name = "steering";
    options.interface = "overlayd-test-none"; // never exists: the socket is retried, frames come from the test
    options.id = {0x25, false};
    options.layout = {7, 16, true, true, 0.1, 0.0};
    options.unit = "deg";
    options.min = -540.0, options.max = 540.0;
    options.timeoutMs = 500;
    options.step = 0.5;
    options.target = {CanTarget::Kind::Steering, "guide lines"};
    return options;
}

CanFrame frame(std::initializer_list<uint8_t> bytes)
{
    CanFrame out;
    out.id = {0x25, false};
    for (uint8_t b : bytes)
        out.data[out.length++] = b;
    return out;
}

// The raw 16-bit value, high byte first.
CanFrame angleFrame(int16_t raw)
{
    return frame({uint8_t(uint16_t(raw) >> 8), uint8_t(raw & 0xFF)});
}

struct CanInputsTest : test::RecordingSceneTest {
    std::vector<std::string> logged;
    Logger logger{[this](std::string_view line) { logged.emplace_back(line); }, true};
    CanInputs can{logger, control};
    Clock::time_point t0 = Clock::now();

    void SetUp() override
    {
        control.load(reverseScene(), CameraSpec{});
        attachStream();
    }
    const GuideLinesShape &guide() const { return std::get<GuideLinesShape>(control.scene().annotations[0].shape); }
};

TEST_F(CanInputsTest, UnknownUntilTheFirstFrameThenTheRoadWheelAngle)
{
    can.configure({steering()});
    ASSERT_EQ(renderer->steerings.size(), 1u);
    EXPECT_EQ(renderer->steerings[0].second, std::nullopt) << "no frame yet: the wheel tracks must not show";
    EXPECT_FALSE(can.reading(0).connected);
    EXPECT_NE(can.reading(0).error.find("overlayd-test-none"), std::string::npos) << can.reading(0).error;

    can.onFrame(0, angleFrame(4000), t0); // 400.0 deg at the wheel, / 15 on the road
    ASSERT_EQ(renderer->steerings.size(), 2u);
    ASSERT_TRUE(renderer->steerings[1].second.has_value());
    EXPECT_NEAR(*renderer->steerings[1].second, 400.0 / 15.0, 1e-12);
    EXPECT_TRUE(guide().steeringKnown);
    EXPECT_NEAR(guide().steeringDeg, 400.0 / 15.0, 1e-12);
    EXPECT_EQ(can.reading(0).state, CanInputs::State::Ok);

    can.onFrame(0, angleFrame(-3000), t0 + 10ms); // 0xF448: negative, two's complement
    EXPECT_NEAR(*renderer->steerings.back().second, -300.0 / 15.0, 1e-12);
}

TEST_F(CanInputsTest, ASteadyWheelCostsNothingBelowTheStep)
{
    can.configure({steering()});
    can.onFrame(0, angleFrame(1000), t0);
    const size_t calls = renderer->steerings.size();
    for (int i = 0; i < 100; ++i) // 100.0 .. 100.4 deg: within the 0.5 deg step of what is shown
        can.onFrame(0, angleFrame(int16_t(1000 + i % 5)), t0 + i * 10ms);
    EXPECT_EQ(renderer->steerings.size(), calls);
    can.onFrame(0, angleFrame(1005), t0 + 1s); // 100.5: one step away
    EXPECT_EQ(renderer->steerings.size(), calls + 1);
    EXPECT_EQ(can.reading(0).frames, 102u);
}

TEST_F(CanInputsTest, MalformedFrameIsCountedAndChangesNothing)
{
    can.configure({steering()});
    can.onFrame(0, angleFrame(1000), t0);
    const size_t calls = renderer->steerings.size();
    can.onFrame(0, frame({0x7F}), t0 + 10ms); // DLC 1: the signal needs 2 bytes
    EXPECT_EQ(can.reading(0).malformed, 1u);
    EXPECT_EQ(can.reading(0).value, 100.0);
    EXPECT_EQ(can.reading(0).state, CanInputs::State::Ok);
    EXPECT_EQ(renderer->steerings.size(), calls);
}

TEST_F(CanInputsTest, OutOfRangeAndSilenceBothHideTheWheelTracks)
{
    can.configure({steering()});
    can.onFrame(0, angleFrame(1000), t0);
    can.onFrame(0, angleFrame(6000), t0 + 10ms); // 600 deg: beyond max 540
    EXPECT_EQ(can.reading(0).state, CanInputs::State::OutOfRange);
    EXPECT_EQ(renderer->steerings.back().second, std::nullopt);
    EXPECT_FALSE(guide().steeringKnown);

    can.onFrame(0, angleFrame(1000), t0 + 20ms);
    EXPECT_TRUE(guide().steeringKnown);
    can.tick(t0 + 20ms + 499ms);
    EXPECT_TRUE(guide().steeringKnown) << "not yet past timeout_ms";
    can.tick(t0 + 20ms + 501ms);
    EXPECT_EQ(can.reading(0).state, CanInputs::State::Stale);
    EXPECT_FALSE(guide().steeringKnown);
    EXPECT_EQ(renderer->steerings.back().second, std::nullopt);
}

TEST_F(CanInputsTest, ARoadWheelAngleTheGeometryCannotDrawIsUnknown)
{
    auto options = steering();
    options.layout.scale = 1.0; // now 100 raw = 100 deg at the wheel ...
    options.max = 5000.0;
    can.configure({options});
    can.onFrame(0, angleFrame(1500), t0); // ... and 1500 / 15 = 100 deg on the road: past the 80 deg the config allows
    EXPECT_EQ(can.reading(0).state, CanInputs::State::Ok);
    EXPECT_FALSE(guide().steeringKnown);
}

TEST_F(CanInputsTest, SlotTargetShowsTheValueWithUnitOrTheStaleText)
{
    CanInputOptions speed = steering();
    speed.name = "speed";
    speed.layout = {0, 8, false, false, 0.5, -10.0}; // Intel byte 0
    speed.unit = "km/h";
    speed.decimals = 1;
    speed.min = -10.0, speed.max = 120.0;
    speed.step = 0.0;
    speed.staleText = "no speed";
    speed.target = {CanTarget::Kind::Slot, "speed"};
    can.configure({speed});
    EXPECT_EQ(control.slotText("speed"), "no speed");
    can.onFrame(0, frame({101}), t0); // 101 * 0.5 - 10
    EXPECT_EQ(control.slotText("speed"), "40.5 km/h");
    can.tick(t0 + 600ms);
    EXPECT_EQ(control.slotText("speed"), "no speed");
}

TEST_F(CanInputsTest, AReloadKeepsAnUnchangedInputsValueAndShowsItOnTheNewScene)
{
    can.configure({steering()});
    can.onFrame(0, angleFrame(1500), t0);
    control.load(reverseScene(), CameraSpec{}); // a reload's new scene: the config's own steering_deg
    EXPECT_TRUE(guide().steeringKnown);
    EXPECT_EQ(guide().steeringDeg, 0.0);
    can.configure({steering()});
    EXPECT_EQ(can.reading(0).frames, 1u) << "the same input keeps its reading";
    EXPECT_NEAR(guide().steeringDeg, 10.0, 1e-12);

    auto changed = steering();
    changed.timeoutMs = 800;
    can.configure({changed});
    EXPECT_EQ(can.reading(0).frames, 0u) << "a changed input starts afresh";
    EXPECT_FALSE(guide().steeringKnown);
}

TEST_F(CanInputsTest, AMissingInterfaceIsWaitingAndItsErrorCountedOncePerReason)
{
    can.configure({steering()});
    std::vector<InputHealth> health = can.health();
    ASSERT_EQ(health.size(), 1u);
    EXPECT_EQ(health[0].kind, "can");
    EXPECT_EQ(health[0].name, "steering");
    EXPECT_EQ(health[0].source, "overlayd-test-none");
    EXPECT_EQ(health[0].state, InputHealth::State::Waiting);
    EXPECT_EQ(health[0].errors, 1u);
    EXPECT_EQ(health[0].lastError, can.reading(0).error);
    EXPECT_FALSE(health[0].lastError.empty());
    can.tick(t0 + 1500ms); // retried, refused for the same reason: not a new error
    can.tick(t0 + 3000ms);
    EXPECT_EQ(can.health()[0].errors, 1u);
    can.configure({steering()});
    EXPECT_EQ(can.health()[0].errors, 1u) << "the same input keeps its health";
}

} // namespace
} // namespace overlayd
