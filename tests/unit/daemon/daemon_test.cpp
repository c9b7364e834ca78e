// Daemon: start-up, READY after the first frame, reloads (bad ones keep the old config and lose no frames; good
// ones switch between two frames), DeviceLost -> NO SIGNAL frames and back-off, the watchdog rule, the end of
// the source. The loop's handlers are called directly; the stages are fakes.
#include "daemon/daemon.h"

#include <map>

#include <gtest/gtest.h>

#include "fakes.h"

namespace overlayd {
namespace {

using test::FakeSource;
using test::RecordingSink;

struct DaemonTest : ::testing::Test {
    std::vector<std::string> logLines;
    Logger logger{[this](std::string_view line) { logLines.emplace_back(line); }, true};
    test::RecordingNotifier notifier;
    std::shared_ptr<FakeSource::Shared> source = std::make_shared<FakeSource::Shared>();
    std::map<std::string, std::shared_ptr<RecordingSink::Shared>> sinks;
    bool rendererFails = false;
    // What the config file says now: a config, or problems.
    std::optional<DaemonConfig> file = makeConfig(1, "a");
    std::vector<ConfigProblem> fileProblems;

    // `mark` is the number of annotations: MarkingRenderer writes it into each frame it blends.
    static DaemonConfig makeConfig(size_t mark, const std::string &sinkPath)
    {
        DaemonConfig config;
        config.path = "test.toml";
        config.source.kind = SourceKind::Synthetic;
        config.source.synthetic.pattern = SyntheticPattern::ColourBars;
        config.source.pixelFormat = pixelFormatFromName("GREY");
        config.source.width = 64;
        config.source.height = 48;
        config.scene.annotations.resize(mark, Annotation{"a", "world", {}, AxesShape{}});
        SinkOptions sink;
        sink.kind = SinkKind::Null;
        sink.path = sinkPath;
        config.sinks.push_back(sink);
        config.daemon.statsIntervalSec = 0;
        return config;
    }

    StageFactories factories()
    {
        StageFactories f;
        f.source = [this](const SourceOptions &, const Camera *) -> Result<std::unique_ptr<FrameSource>> {
            return std::unique_ptr<FrameSource>(std::make_unique<FakeSource>(source, test::greyFormat()));
        };
        f.sink = [this](const SinkOptions &options) -> Result<std::unique_ptr<FrameSink>> {
            auto &shared = sinks[options.path];
            if (!shared)
                shared = std::make_shared<RecordingSink::Shared>();
            return std::unique_ptr<FrameSink>(std::make_unique<RecordingSink>(shared, options.path));
        };
        f.renderer = [this](const OverlayScene &scene, const Camera &,
                            const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
            if (rendererFails)
                return makeError(ErrorCode::InvalidArgument, "annotation 'a': unknown frame 'base'");
            return std::unique_ptr<OverlayRenderer>(
                std::make_unique<test::MarkingRenderer>(uint8_t(scene.annotations.size())));
        };
        return f;
    }

    std::unique_ptr<Daemon> makeDaemon(uint64_t maxFrames = 0)
    {
        ConfigLoader loader = [this](const std::string &,
                                     std::vector<ConfigProblem> &problems) -> Result<DaemonConfig> {
            if (file)
                return *file;
            problems = fileProblems;
            return makeError(ErrorCode::ConfigError, "invalid");
        };
        return std::make_unique<Daemon>(logger, notifier, factories(), loader,
                                        DaemonOptions{"test.toml", std::nullopt, maxFrames});
    }

    bool logged(const std::string &text) const
    {
        for (const std::string &line : logLines)
            if (line.find(text) != std::string::npos)
                return true;
        return false;
    }
};

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
    EXPECT_NE(
        std::find_if(reloading, notifier.events.end(),
                     [](const std::string &e) { return e.find("kept the previous config") != std::string::npos; }),
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
