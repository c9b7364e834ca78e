// SPDX-License-Identifier: Apache-2.0
// Daemon: start-up, READY after the first frame, DeviceLost -> NO SIGNAL frames and back-off, the watchdog rule, the
// end of the source (reloads: reload_test.cpp). The loop's handlers are called directly; the stages are fakes.
#include "daemon/daemon.h"

#include <gtest/gtest.h>

#include "daemon_fixture.h"

namespace overlayd {
namespace {

using test::DaemonTest;

TEST_F(DaemonTest, ReadyOnlyAfterTheFirstFrame)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    EXPECT_EQ(notifier.count("READY"), 0);
    daemon->onFrameReady();
    EXPECT_EQ(notifier.count("READY"), 1);
    daemon->onFrameReady();
    EXPECT_EQ(notifier.count("READY"), 1);
    EXPECT_EQ(notifier.lastStatus(), "streaming 64x48 GREY 30.0 fps, 0 drops");
}

TEST_F(DaemonTest, FramesAreBlendedAndReachTheSink)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    for (int i = 0; i < 3; ++i)
        daemon->onFrameReady();
    daemon.reset(); // flushes and closes the sinks
    EXPECT_EQ(sinks["a"]->firstBytes, (std::vector<uint8_t>{0, 1, 2}));
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1, 1}));
    EXPECT_EQ(sinks["a"]->closes, 1);
}

TEST_F(DaemonTest, DeviceLostFeedsNoSignalFramesAndRetriesWithBackoff)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    source->script.push_back(makeError(ErrorCode::DeviceLost, "/dev/video0: ENODEV"));
    daemon->onFrameReady();
    EXPECT_EQ(daemon->state(), Daemon::State::Waiting);
    EXPECT_EQ(daemon->waitReason(), "/dev/video0: ENODEV");
    EXPECT_EQ(source->stops, 1);
    EXPECT_NE(notifier.lastStatus().find("/dev/video0: ENODEV, retry in 0.5 s"), std::string::npos)
        << notifier.lastStatus();

    daemon->onNoSignalTick();
    daemon->onNoSignalTick();
    source->startErrors.push_back(makeError(ErrorCode::DeviceLost, "/dev/video0: ENODEV"));
    daemon->onRetry(); // still gone: the next delay doubles
    EXPECT_EQ(daemon->state(), Daemon::State::Waiting);
    EXPECT_NE(notifier.lastStatus().find("retry in 1 s"), std::string::npos) << notifier.lastStatus();
    daemon->onRetry(); // back
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    EXPECT_EQ(daemon->nextRetryDelay(), std::chrono::milliseconds(500));
    daemon->onNoSignalTick(); // streaming again: no more NO SIGNAL frames
    daemon->onFrameReady();
    daemon.reset();

    const auto &sink = *sinks["a"];
    ASSERT_EQ(sink.maxima.size(), 4u); // a frame, two NO SIGNAL frames, a frame
    EXPECT_EQ(sink.maxima[0], 1);      // source frames: zero but for the sequence and the renderer's mark
    EXPECT_GT(sink.maxima[1], 200);    // white text on the NO SIGNAL frame
    EXPECT_GT(sink.maxima[2], 200);
    EXPECT_EQ(sink.lastBytes[3], 1);
}

// A camera that stops delivering without an error (a wedged driver, one libcamera lost track of) is torn down when
// its no_signal_timeout runs out (the loop's timer fires onNoSignalTick), and then waited for like a lost one. Files
// and synthetic sources have no such timeout.
TEST_F(DaemonTest, StalledCameraIsTornDownAfterItsNoSignalTimeout)
{
    for (const SourceKind kind : {SourceKind::V4l2, SourceKind::Libcamera}) {
        file->source.kind = kind;
        file->source.v4l2.noSignalTimeoutSec = 1.5;
        file->source.libcamera.noSignalTimeoutSec = 1.5;
        auto daemon = makeDaemon();
        ASSERT_TRUE(daemon->start().ok());
        daemon->onFrameReady();
        EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
        daemon->onNoSignalTick(); // the timer, re-armed by every frame, ran out
        EXPECT_EQ(daemon->state(), Daemon::State::Waiting);
        EXPECT_EQ(daemon->waitReason(), "fake source: no frame for 1.5 s");
        daemon->onRetry();
        EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    }
    file->source.kind = SourceKind::Synthetic;
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    daemon->onNoSignalTick();
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
}

TEST_F(DaemonTest, AbsentSourceAtStartIsWaitedForWithTheConfiguredFormat)
{
    source->startErrors.push_back(makeError(ErrorCode::DeviceLost, "no camera yet"));
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    EXPECT_EQ(daemon->state(), Daemon::State::Waiting);
    EXPECT_EQ(daemon->pipeline().format().width, 64u);
    EXPECT_EQ(sinks["a"]->opens, 1);
    EXPECT_EQ(notifier.count("READY"), 0); // nothing went through yet
}

TEST_F(DaemonTest, WatchdogIsPettedOnlyWhileFramesFlowOrAReconnectRuns)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onWatchdog();
    EXPECT_EQ(notifier.count("WATCHDOG"), 0);
    daemon->onFrameReady();
    daemon->onWatchdog();
    EXPECT_EQ(notifier.count("WATCHDOG"), 1);
    daemon->onWatchdog(); // a wedged source: no frame since the last pet
    EXPECT_EQ(notifier.count("WATCHDOG"), 1);
    source->script.push_back(makeError(ErrorCode::DeviceLost, "gone"));
    daemon->onFrameReady();
    daemon->onWatchdog(); // a deliberate reconnect
    EXPECT_EQ(notifier.count("WATCHDOG"), 2);
}

TEST_F(DaemonTest, EndOfStreamEndsCleanly)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    source->script.push_back(makeError(ErrorCode::EndOfStream, "end"));
    daemon->onFrameReady();
    EXPECT_EQ(daemon->state(), Daemon::State::Finished);
    EXPECT_EQ(daemon->exitStatus(), 0);
}

TEST_F(DaemonTest, MalformedInputEndsWithFailureNamingIt)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    source->script.push_back(makeError(ErrorCode::Malformed, "in.y4m: frame 3 is truncated"));
    daemon->onFrameReady();
    EXPECT_EQ(daemon->state(), Daemon::State::Finished);
    EXPECT_EQ(daemon->exitStatus(), 1);
    EXPECT_TRUE(logged("in.y4m: frame 3 is truncated"));
}

TEST_F(DaemonTest, FrameLimitStopsAfterExactlyThatMany)
{
    auto daemon = makeDaemon(3);
    ASSERT_TRUE(daemon->start().ok());
    for (int i = 0; i < 3; ++i)
        daemon->onFrameReady();
    EXPECT_EQ(daemon->state(), Daemon::State::Finished);
    daemon.reset();
    EXPECT_EQ(sinks["a"]->sequences.size(), 3u);
}

TEST_F(DaemonTest, BadConfigAtStartIsRefusedWithEveryProblem)
{
    file.reset();
    fileProblems = {ConfigProblem{"test.toml", 2, 1, "source.width", "must be <= 16384 (got 100000)"}};
    auto daemon = makeDaemon();
    const Status started = daemon->start();
    ASSERT_FALSE(started.ok());
    EXPECT_EQ(started.error().code, ErrorCode::ConfigError);
    EXPECT_TRUE(logged("<3>test.toml:2:1: source.width: must be <= 16384 (got 100000)"));
}

} // namespace
} // namespace overlayd
