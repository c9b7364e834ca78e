// SPDX-License-Identifier: Apache-2.0
// Daemon::reload as a transaction: a bad file, an overlay, a source or a sink that cannot be built or opened
// refuses the reload with the old config still running as it was; a good one switches between two frames, opening
// a new source before the running one closes unless both may be the same device.
#include "daemon/daemon.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "daemon_fixture.h"

namespace overlayd {
namespace {

using test::DaemonTest;

TEST_F(DaemonTest, BadReloadKeepsTheOldConfigAndLosesNoFrames)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    file.reset();
    fileProblems = {ConfigProblem{"test.toml", 7, 3, "source.fps", "must be > 0 (got 0)"},
                    ConfigProblem{"test.toml", 9, 1, "sink[0].kidn", "unknown key; did you mean 'kind'?"}};
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(logged("test.toml:7:3: source.fps: must be > 0 (got 0)"));
    EXPECT_TRUE(logged("test.toml:9:1: sink[0].kidn: unknown key; did you mean 'kind'?"));
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(source->starts, 1); // the source was not touched
    EXPECT_EQ(sinks["a"]->opens, 1);
    EXPECT_EQ(sinks["a"]->sequences, (std::vector<uint64_t>{0, 1}));
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1}));
    // systemd hears RELOADING, a STATUS saying the old config was kept, then READY again.
    const auto reloading = std::find(notifier.events.begin(), notifier.events.end(), "RELOADING");
    ASSERT_NE(reloading, notifier.events.end());
    EXPECT_NE(std::find_if(reloading, notifier.events.end(),
                           [](const std::string &e) {
                               return e.find("reload refused, kept the previous config") != std::string::npos;
                           }),
              notifier.events.end());
    EXPECT_EQ(notifier.events.back(), "READY");
}

TEST_F(DaemonTest, ReloadWhoseOverlayCannotBeBuiltKeepsTheOldOne)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    file = makeConfig(2, "a");
    rendererFails = true;
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(logged("unknown frame 'base'"));
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1})); // still the old overlay
}

TEST_F(DaemonTest, GoodReloadSwitchesOverlayAndSinksBetweenTwoFrames)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    daemon->onFrameReady();
    file = makeConfig(2, "b");
    EXPECT_TRUE(daemon->reload());
    daemon->onFrameReady();
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(source->starts, 1); // same source options: not re-opened
    EXPECT_EQ(sinks["a"]->sequences, (std::vector<uint64_t>{0, 1}));
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1}));
    EXPECT_EQ(sinks["a"]->closes, 1);
    EXPECT_EQ(sinks["b"]->sequences, (std::vector<uint64_t>{2, 3}));
    EXPECT_EQ(sinks["b"]->lastBytes, (std::vector<uint8_t>{2, 2}));
}

TEST_F(DaemonTest, ReloadWhoseSourceCannotOpenKeepsTheRunningOne)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    file = makeConfig(2, "a");
    file->source.width = 32; // another source
    source->startErrors.push_back(makeError(ErrorCode::NotFound, "missing.y4m: No such file or directory"));
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(
        logged("reload refused, kept the previous config: test.toml: source: fake source: missing.y4m: No such file"));
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    EXPECT_EQ(source->stops, 0); // the running source was never closed
    EXPECT_EQ(notifier.lastStatus(),
              "reload refused, kept the previous config: test.toml: source: fake source: missing.y4m: No such file or "
              "directory");
    daemon->onFrameReady();
    daemon->onStats(); // each STATUS= while the old config streams on says so
    EXPECT_NE(notifier.lastStatus().find("streaming 64x48 GREY 30.0 fps, 0 drops; last reload refused: test.toml"),
              std::string::npos)
        << notifier.lastStatus();
    daemon.reset();
    EXPECT_EQ(sinks["a"]->sequences, (std::vector<uint64_t>{0, 1}));
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1})); // the old overlay
    EXPECT_EQ(sinks["a"]->opens, 1);
}

TEST_F(DaemonTest, GoodReloadOpensTheNewSourceBeforeClosingTheRunningOne)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    file = makeConfig(2, "a");
    file->source.width = 32;
    EXPECT_TRUE(daemon->reload());
    EXPECT_TRUE(logged("reloaded test.toml (source re-opened)"));
    EXPECT_EQ(source->mostRunning, 2);
    EXPECT_EQ(source->running, 1);
    EXPECT_EQ(daemon->pipeline().format().width, 32u);
    EXPECT_EQ(notifier.lastStatus(), "streaming 32x48 GREY 30.0 fps, 0 drops");
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(sinks["a"]->opens, 2); // re-opened for the new format
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 2}));
}

// A V4L2 device cannot be opened twice: the running stream is closed first, and when the new format fails the
// device is opened again as it was.
TEST_F(DaemonTest, SameDeviceInAFormatItRefusesIsReopenedAsItWas)
{
    file->source.kind = SourceKind::V4l2;
    file->source.v4l2.device = "/dev/overlayd-test-video";
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    DaemonConfig next = *file;
    next.source.width = 32;
    file = next;
    source->startErrors.push_back(makeError(ErrorCode::Io, "VIDIOC_S_FMT: Device or resource busy"));
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(logged("test.toml: source: fake source: VIDIOC_S_FMT: Device or resource busy"));
    EXPECT_EQ(source->mostRunning, 1); // never two streams on one device
    EXPECT_EQ(source->starts, 3);      // the running format, the new one, the running one again
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    EXPECT_EQ(daemon->pipeline().format().width, 64u);
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1}));
    EXPECT_EQ(sinks["a"]->opens, 1);
}

TEST_F(DaemonTest, SinkThatCannotOpenRefusesTheReloadAndTheRunningSinksRunOn)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    file = makeConfig(2, "a");
    SinkOptions missing = file->sinks[0];
    missing.path = "no-such-folder/b.y4m";
    file->sinks.push_back(missing);
    sinks[missing.path] = std::make_shared<test::RecordingSink::Shared>();
    sinks[missing.path]->failOpens = 1;
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(logged("reload refused, kept the previous config: test.toml: sink: no-such-folder/b.y4m: cannot open "
                       "for 64x48 GREY 30.0 fps: no-such-folder/b.y4m: No such file or directory"));
    daemon->onFrameReady();
    daemon.reset();
    // The running sink was never closed: the new sink on its path waits for every sink elsewhere to open first.
    EXPECT_EQ(sinks["a"]->opens, 1);
    EXPECT_EQ(sinks["a"]->closes, 1); // at the end
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1}));
}

TEST_F(DaemonTest, NewSinkOnARunningOnesPathThatFailsReopensTheRunningOnesAndTheRunningSource)
{
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    daemon->onFrameReady();
    file = makeConfig(2, "b");
    file->sinks.push_back(file->sinks[0]);
    file->sinks[1].path = "a";
    file->source.width = 32; // a new source too: opened, then given up
    sinks["a"]->failOpens = 1;
    EXPECT_FALSE(daemon->reload());
    EXPECT_TRUE(logged("test.toml: sink: a: cannot open for 32x48 GREY 30.0 fps"));
    EXPECT_EQ(source->mostRunning, 2);
    EXPECT_EQ(source->running, 1);
    EXPECT_EQ(daemon->pipeline().format().width, 64u);
    daemon->onFrameReady();
    daemon.reset();
    EXPECT_EQ(sinks["b"]->opens, 1); // opened while the running sinks ran, closed when the reload was refused
    EXPECT_EQ(sinks["b"]->closes, 1);
    EXPECT_TRUE(sinks["b"]->sequences.empty());
    EXPECT_EQ(sinks["a"]->opens, 3); // at start, the new one that failed, the running one again
    EXPECT_EQ(sinks["a"]->sequences, (std::vector<uint64_t>{0, 1}));
    EXPECT_EQ(sinks["a"]->lastBytes, (std::vector<uint8_t>{1, 1}));
}

TEST_F(DaemonTest, ReloadWhileWaitingNeedsTheNewSourceToOpen)
{
    source->startErrors.push_back(makeError(ErrorCode::DeviceLost, "no camera yet"));
    auto daemon = makeDaemon();
    ASSERT_TRUE(daemon->start().ok());
    ASSERT_EQ(daemon->state(), Daemon::State::Waiting);
    file = makeConfig(2, "a");
    file->source.width = 32;
    source->startErrors.push_back(makeError(ErrorCode::DeviceLost, "no other camera either"));
    EXPECT_FALSE(daemon->reload());
    EXPECT_EQ(daemon->state(), Daemon::State::Waiting);
    EXPECT_EQ(daemon->config().source.width, 64u);
    EXPECT_TRUE(daemon->reload());
    EXPECT_EQ(daemon->state(), Daemon::State::Streaming);
    EXPECT_EQ(daemon->pipeline().format().width, 32u);
}

} // namespace
} // namespace overlayd
