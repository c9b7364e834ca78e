// SPDX-License-Identifier: Apache-2.0
// CameraPresence: the re-acquire state machine. A camera that goes away is waited for; the one that comes back is
// opened again by its id, or by its model when the config names an index; another camera is never taken instead.
#include <gtest/gtest.h>

#include "drivers/libcamera/camera_presence.h"

namespace overlayd {
namespace {

const CameraIdentity kSensorB{"platform/vimc.0 Sensor B", "Sensor B"};
const CameraIdentity kSensorA{"platform/vimc.0 Sensor A", "Sensor A"};
const CameraIdentity kImx219{"/base/soc/i2c0mux/i2c@1/imx219@10", "imx219"};

CameraEvent event(CameraEvent::Kind kind, const CameraIdentity &camera)
{
    return {kind, camera.id, camera.model};
}

TEST(CameraPresence, SpecRulesBeforeTheFirstOpen)
{
    const std::vector<CameraIdentity> present{kSensorA, kSensorB};
    EXPECT_EQ(matchCameraSpec("0", present), 0u);
    EXPECT_EQ(matchCameraSpec("1", present), 1u);
    EXPECT_EQ(matchCameraSpec("2", present), std::nullopt);
    EXPECT_EQ(matchCameraSpec("platform/vimc.0 Sensor B", present), 1u);
    EXPECT_EQ(matchCameraSpec("Sensor B", present), 1u); // a model substring
    EXPECT_EQ(matchCameraSpec("imx", present), std::nullopt);
    EXPECT_EQ(CameraPresence("1").choose(present), 1u);
}

TEST(CameraPresence, DisconnectedWhileStreamingIsLostThenWaitedFor)
{
    CameraPresence presence("0");
    EXPECT_EQ(presence.state(), CameraPresence::State::Closed);
    presence.opened(kSensorB);
    EXPECT_EQ(presence.state(), CameraPresence::State::Streaming);
    presence.apply(event(CameraEvent::Kind::Disconnected, {}));
    EXPECT_TRUE(presence.lost());
    presence.closed(); // the loop stops the source: still waiting for the same camera
    EXPECT_EQ(presence.state(), CameraPresence::State::Gone);
    EXPECT_EQ(presence.choose({}), std::nullopt);
    EXPECT_EQ(presence.awaited(), "'Sensor B' (platform/vimc.0 Sensor B)");
}

TEST(CameraPresence, RemovalOfAnotherCameraIsIgnored)
{
    CameraPresence presence("0");
    presence.opened(kSensorB);
    presence.apply(event(CameraEvent::Kind::Removed, kSensorA));
    EXPECT_FALSE(presence.lost());
    presence.apply(event(CameraEvent::Kind::Removed, kSensorB));
    EXPECT_TRUE(presence.lost());
}

TEST(CameraPresence, IndexSpecComesBackByModelNotByPosition)
{
    CameraPresence presence("0");
    presence.opened(kSensorB);
    presence.apply(event(CameraEvent::Kind::Removed, kSensorB));
    presence.closed();
    // Meanwhile another camera is first in the list: "0" no longer means it.
    EXPECT_EQ(presence.choose({kImx219}), std::nullopt);
    presence.apply(event(CameraEvent::Kind::Added, kImx219));
    EXPECT_FALSE(presence.cameBack());
    // The same model under another id (plugged into another port) is the configured camera.
    const CameraIdentity moved{"platform/vimc.1 Sensor B", "Sensor B"};
    presence.apply(event(CameraEvent::Kind::Added, moved));
    EXPECT_TRUE(presence.cameBack());
    EXPECT_EQ(presence.choose({kImx219, moved}), 1u);
    presence.opened(moved);
    EXPECT_EQ(presence.state(), CameraPresence::State::Streaming);
    EXPECT_FALSE(presence.cameBack());
}

TEST(CameraPresence, SameIdPreferredOverSameModel)
{
    CameraPresence presence("0");
    presence.opened(kSensorB);
    presence.apply(event(CameraEvent::Kind::Disconnected, {}));
    const CameraIdentity twin{"platform/vimc.1 Sensor B", "Sensor B"};
    EXPECT_EQ(presence.choose({twin, kSensorB}), 1u);
}

TEST(CameraPresence, IdSpecWaitsForThatIdOnly)
{
    CameraPresence presence(kSensorB.id);
    presence.opened(kSensorB);
    presence.apply(event(CameraEvent::Kind::Disconnected, {}));
    presence.closed();
    const CameraIdentity twin{"platform/vimc.1 Sensor B", "Sensor B"};
    presence.apply(event(CameraEvent::Kind::Added, twin));
    EXPECT_FALSE(presence.cameBack());
    EXPECT_EQ(presence.choose({twin}), std::nullopt);
    presence.apply(event(CameraEvent::Kind::Added, kSensorB));
    EXPECT_TRUE(presence.cameBack());
    EXPECT_EQ(presence.choose({twin, kSensorB}), 1u);
}

TEST(CameraPresence, AStopThatIsNoLossForgetsNothingButWaitsForNothing)
{
    CameraPresence presence("0");
    presence.opened(kSensorB);
    presence.closed();
    EXPECT_EQ(presence.state(), CameraPresence::State::Closed);
    EXPECT_FALSE(presence.lost());
    presence.apply(event(CameraEvent::Kind::Disconnected, {})); // a late event of the closed camera
    EXPECT_FALSE(presence.lost());
    EXPECT_EQ(presence.choose({kSensorA, kSensorB}), 1u);
}

TEST(CameraPresence, ARememberedCameraIsChosenAsIfThisPresenceHadOpenedIt)
{
    // The daemon's next retry is a new source: it is told which camera the last one opened.
    CameraPresence presence("0");
    presence.remember(kSensorB);
    EXPECT_EQ(presence.state(), CameraPresence::State::Closed);
    EXPECT_EQ(presence.choose({kSensorA}), std::nullopt); // not whatever is first now
    EXPECT_EQ(presence.choose({kSensorA, kSensorB}), 1u);
    EXPECT_EQ(presence.awaited(), "'Sensor B' (platform/vimc.0 Sensor B)");
    presence.opened(kSensorB);
    EXPECT_EQ(presence.state(), CameraPresence::State::Streaming);
}

} // namespace
} // namespace overlayd