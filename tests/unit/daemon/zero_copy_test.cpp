// SPDX-License-Identifier: Apache-2.0
// Zero copy through the daemon: a lease-taking sink gets a reference to the source's own buffer (given back when
// its last holder drops it, on whatever thread), every other sink a copy; the stats say how many; the config key
// and what it makes the source do.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "config/daemon_config.h"
#include "daemon/pipeline.h"
#include "daemon/stages.h"
#include "fakes.h"
#include "stream/stream_options.h"

namespace overlayd {
namespace {

// Takes frames that carry a dmabuf fd and holds them until release(), as a V4L2 output holds them until DQBUF.
class HoldingSink : public FrameSink
{
public:
    Status open(const StreamFormat &) override { return Ok{}; }
    Status write(const FrameView &frame, const FrameMetadata &) override
    {
        std::lock_guard lock(mutex_);
        copiedData_.push_back(frame.planes[0].data);
        return Ok{};
    }
    Status close() override
    {
        release();
        return Ok{};
    }
    std::string describe() const override { return "holding"; }
    bool takesLease(const FrameView &frame) const override { return frame.planes[0].dmabufFd >= 0; }
    Status writeLease(std::shared_ptr<const FrameLease> lease) override
    {
        std::lock_guard lock(mutex_);
        writerThread_ = std::this_thread::get_id();
        held_.push_back(std::move(lease));
        return Ok{};
    }
    void release()
    {
        std::lock_guard lock(mutex_);
        held_.clear();
    }
    size_t held()
    {
        std::lock_guard lock(mutex_);
        return held_.size();
    }
    const uint8_t *heldData(size_t i)
    {
        std::lock_guard lock(mutex_);
        return held_.at(i)->view().planes[0].data;
    }
    std::thread::id writerThread()
    {
        std::lock_guard lock(mutex_);
        return writerThread_;
    }

private:
    std::mutex mutex_;
    std::vector<std::shared_ptr<const FrameLease>> held_;
    std::vector<const uint8_t *> copiedData_;
    std::thread::id writerThread_;
};

struct ZeroCopyPipeline : ::testing::Test {
    Logger logger{[](std::string_view) {}, true};
    StreamFormat format = test::greyFormat();
    FrameBuffer camera = std::move(FrameBuffer::allocate(format).value());
    std::atomic<int> givenBack{0};
    std::shared_ptr<test::RecordingSink::Shared> recorded = std::make_shared<test::RecordingSink::Shared>();
    HoldingSink *holding = nullptr;

    FrameLease lease(uint8_t value, int fd = 7)
    {
        FrameView view = camera.view();
        view.planes[0].dmabufFd = fd;
        view.planes[0].data[0] = value;
        FrameMetadata metadata;
        metadata.sequence = value;
        return FrameLease(view, metadata, [this] { ++givenBack; });
    }

    void waitWritten(SinkWorker &worker, uint64_t count)
    {
        while (worker.counters().written + worker.counters().failed < count)
            std::this_thread::yield();
    }

    Pipeline pipeline{logger}; // last: its sinks give leases back into the members above when it goes

    void addBothSinks()
    {
        std::vector<std::unique_ptr<SinkWorker>> sinks;
        auto sink = std::make_unique<HoldingSink>();
        holding = sink.get();
        sinks.push_back(std::make_unique<SinkWorker>(std::move(sink), SinkOptions{}, logger));
        sinks.push_back(std::make_unique<SinkWorker>(std::make_unique<test::RecordingSink>(recorded, "copy"),
                                                     SinkOptions{}, logger));
        pipeline.setSinks(std::move(sinks));
        EXPECT_TRUE(pipeline.openSinks(format).ok());
    }
};

TEST_F(ZeroCopyPipeline, ALeaseTakingSinkHoldsTheSourcesBufferAndTheLastHolderGivesItBack)
{
    addBothSinks();
    pipeline.process(lease(5));
    waitWritten(*pipeline.sinks()[0], 1);
    waitWritten(*pipeline.sinks()[1], 1);
    ASSERT_EQ(holding->held(), 1u);
    EXPECT_EQ(holding->heldData(0), camera.data()); // the very buffer, not a copy
    EXPECT_NE(holding->writerThread(), std::this_thread::get_id());
    EXPECT_EQ(recorded->firstBytes, std::vector<uint8_t>{5}); // the other sink got its copy
    EXPECT_EQ(givenBack, 0);
    holding->release();
    EXPECT_EQ(givenBack, 1);
    EXPECT_EQ(pipeline.sinks()[0]->counters().zeroCopy, 1u);
    EXPECT_EQ(pipeline.sinks()[1]->counters().zeroCopy, 0u);
    EXPECT_NE(pipeline.takeStats().describe().find("holding: out "), std::string::npos);
}

TEST_F(ZeroCopyPipeline, StatsLineCountsZeroCopyFrames)
{
    addBothSinks();
    for (uint8_t i = 0; i < 3; ++i)
        pipeline.process(lease(i));
    waitWritten(*pipeline.sinks()[0], 3);
    const std::string line = pipeline.takeStats().describe();
    EXPECT_NE(line.find("write 0."), std::string::npos) << line;
    EXPECT_NE(line.find(" ms, 3 zero-copy; copy: out"), std::string::npos) << line;
}

TEST_F(ZeroCopyPipeline, StatsLineSaysHowTheLastFrameWasExposedWhenTheCameraReportsIt)
{
    addBothSinks();
    pipeline.process(lease(1));
    EXPECT_EQ(pipeline.takeStats().describe().find("exposure"), std::string::npos);
    FrameLease exposed = lease(2);
    exposed.metadata().exposureUs = 16600;
    exposed.metadata().analogueGain = 2.5f;
    pipeline.process(std::move(exposed));
    const std::string line = pipeline.takeStats().describe();
    EXPECT_NE(line.find(" ms, exposure 16600 us, gain 2.50; holding: out"), std::string::npos) << line;
}

TEST_F(ZeroCopyPipeline, FramesWithoutFdsAreCopiedAndGivenBackAtOnce)
{
    addBothSinks();
    pipeline.process(lease(9, -1));
    EXPECT_EQ(givenBack, 1); // both sinks copied before process() returned
    ASSERT_TRUE(pipeline.sinks()[0]->close().ok());
    EXPECT_EQ(holding->held(), 0u);
    EXPECT_EQ(pipeline.sinks()[0]->counters().written, 1u);
    EXPECT_EQ(pipeline.sinks()[0]->counters().zeroCopy, 0u);
}

TEST_F(ZeroCopyPipeline, ADroppedQueuedLeaseIsGivenBack)
{
    auto sink = std::make_unique<test::RecordingSink>(recorded, "slow");
    // A sink that takes leases but is stuck: the queue fills with references, the oldest are dropped.
    struct StuckLeaseSink : test::RecordingSink {
        using RecordingSink::RecordingSink;
        bool takesLease(const FrameView &) const override { return true; }
        Status writeLease(std::shared_ptr<const FrameLease> lease) override
        {
            return write(lease->view(), lease->metadata()); // blocks while the gate is closed
        }
    };
    SinkOptions options;
    options.queueDepth = 2;
    SinkWorker worker(std::make_unique<StuckLeaseSink>(recorded, "stuck"), options, logger);
    ASSERT_TRUE(worker.open(format).ok());
    recorded->setGate(false);
    worker.push(std::make_shared<const FrameLease>(lease(0)));
    recorded->waitEntered(1);
    for (uint8_t i = 1; i <= 5; ++i)
        worker.push(std::make_shared<const FrameLease>(lease(i)));
    EXPECT_EQ(worker.counters().dropped, 3u);
    EXPECT_EQ(givenBack, 3); // 1, 2, 3 dropped; 0 is being written, 4 and 5 are queued
    recorded->setGate(true);
    ASSERT_TRUE(worker.close().ok());
    EXPECT_EQ(givenBack, 6);
    EXPECT_EQ(recorded->sequences, (std::vector<uint64_t>{0, 4, 5}));
}

TEST_F(ZeroCopyPipeline, AnInlineSinkTakesTheLeaseOnTheCallersThread)
{
    // The encoded stream's form: it hands the lease to the encoder at once, so the worker has no queue for it.
    struct InlineHoldingSink : HoldingSink {
        bool writesInline() const override { return true; }
    };
    auto sink = std::make_unique<InlineHoldingSink>();
    HoldingSink *held = sink.get();
    SinkWorker worker(std::move(sink), SinkOptions{}, logger);
    ASSERT_TRUE(worker.open(format).ok());
    worker.push(std::make_shared<const FrameLease>(lease(1)));
    ASSERT_EQ(held->held(), 1u); // written before push() returned
    EXPECT_EQ(held->writerThread(), std::this_thread::get_id());
    EXPECT_EQ(held->heldData(0), camera.view().planes[0].data);
    EXPECT_EQ(worker.counters().written, 1u);
    EXPECT_EQ(worker.counters().zeroCopy, 1u);
    EXPECT_EQ(givenBack, 0);
    held->release();
    EXPECT_EQ(givenBack, 1);
    ASSERT_TRUE(worker.close().ok());
}

DaemonConfig loadText(const std::string &text, std::vector<ConfigProblem> &problems)
{
    auto config = loadConfigText(text, "zero.toml", ".", problems);
    return config ? config.value() : DaemonConfig{};
}

TEST(ZeroCopyConfig, KeyDefaultsToAutoAndMakesTheV4l2SourceExport)
{
    std::vector<ConfigProblem> problems;
    DaemonConfig config = loadText("[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video10\"\n", problems);
    ASSERT_TRUE(problems.empty());
    ASSERT_EQ(config.sinks.size(), 1u);
    EXPECT_EQ(config.sinks[0].zeroCopy, ZeroCopy::Auto);
    EXPECT_TRUE(wantsZeroCopy(config));
    config = loadText("[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video10\"\nzero_copy = \"off\"\n"
                      "[[sink]]\nkind = \"null\"\n",
                      problems);
    ASSERT_TRUE(problems.empty());
    EXPECT_EQ(config.sinks[0].zeroCopy, ZeroCopy::Off);
    EXPECT_FALSE(wantsZeroCopy(config));
    config = loadText("[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video10\"\nzero_copy = \"on\"\n", problems);
    EXPECT_EQ(config.sinks[0].zeroCopy, ZeroCopy::On);
}

TEST(ZeroCopyConfig, BadValuesAndOtherSinkKindsAreProblems)
{
    std::vector<ConfigProblem> problems;
    (void)loadText("[[sink]]\nkind = \"v4l2\"\npath = \"/dev/video10\"\nzero_copy = \"yes\"\n"
                   "[[sink]]\nkind = \"y4m\"\npath = \"x.y4m\"\nzero_copy = \"on\"\n",
                   problems);
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_NE(problems[0].format().find("zero.toml:4:13: sink[0].zero_copy:"), std::string::npos)
        << problems[0].format();
    EXPECT_NE(problems[1].format().find("sink[1].zero_copy: only a kind = \"v4l2\" sink"), std::string::npos)
        << problems[1].format();
}

TEST(ZeroCopyConfig, ChangingZeroCopyChangesTheSinkOptions)
{
    SinkOptions a, b;
    a.kind = b.kind = SinkKind::V4l2Output;
    b.zeroCopy = ZeroCopy::Off;
    EXPECT_FALSE(std::vector<SinkOptions>{a} == std::vector<SinkOptions>{b});
    EXPECT_TRUE(std::vector<SinkOptions>{a} == std::vector<SinkOptions>{a});
}

TEST(ZeroCopyConfig, OnlyOneSinkHoldsTheCamerasBuffers)
{
    const auto v4l2 = [](const std::string &path, ZeroCopy mode) {
        SinkOptions options;
        options.kind = SinkKind::V4l2Output;
        options.path = path;
        options.zeroCopy = mode;
        return options;
    };
    std::vector<SinkOptions> sinks = {v4l2("/a", ZeroCopy::Auto), v4l2("/b", ZeroCopy::On), v4l2("/c", ZeroCopy::Auto),
                                      v4l2("/d", ZeroCopy::Off)};
    std::vector<std::string> notices;
    ASSERT_TRUE(limitZeroCopy(sinks, notices).ok());
    EXPECT_EQ(sinks[0].zeroCopy, ZeroCopy::Off);
    EXPECT_EQ(sinks[1].zeroCopy, ZeroCopy::On);
    EXPECT_EQ(sinks[2].zeroCopy, ZeroCopy::Off);
    EXPECT_EQ(sinks[3].zeroCopy, ZeroCopy::Off);
    EXPECT_EQ(notices, (std::vector<std::string>{
                           "sink /a: copying (zero_copy \"auto\"): /b already takes the camera's buffers",
                           "sink /c: copying (zero_copy \"auto\"): /b already takes the camera's buffers"}));

    sinks = {v4l2("/a", ZeroCopy::Auto), v4l2("/b", ZeroCopy::Auto)};
    notices.clear();
    ASSERT_TRUE(limitZeroCopy(sinks, notices).ok());
    EXPECT_EQ(sinks[0].zeroCopy, ZeroCopy::Auto);
    EXPECT_EQ(sinks[1].zeroCopy, ZeroCopy::Off);

    sinks = {v4l2("/a", ZeroCopy::On), v4l2("/b", ZeroCopy::On)};
    auto refused = limitZeroCopy(sinks, notices);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::ConfigError);
    EXPECT_EQ(refused.error().message,
              "sinks /a and /b both have zero_copy = \"on\"; only one sink can hold the camera's buffers");
}

TEST(ZeroCopyConfig, AV4l2EncoderMakesTheSourceExportUnlessAnOutputHoldsTheBuffers)
{
    DaemonConfig config;
    config.stream.sinks.push_back({EncodedSinkKind::File, "sink[0]", {}, {}, {}, {}});
    config.stream.encoder.kind = EncoderKind::V4l2;
    EXPECT_TRUE(wantsZeroCopy(config));
    config.stream.encoder.zeroCopy = EncoderZeroCopy::Off;
    EXPECT_FALSE(wantsZeroCopy(config));
    config.stream.encoder.zeroCopy = EncoderZeroCopy::Auto;
    config.stream.encoder.kind = EncoderKind::OpenH264; // a software encoder only ever gets copies
    EXPECT_FALSE(wantsZeroCopy(config));

    SinkOptions output;
    output.kind = SinkKind::V4l2Output;
    output.path = "/dev/video10";
    std::vector<std::string> notices;
    EncoderOptions encoder;
    ASSERT_TRUE(limitEncoderZeroCopy({output}, encoder, notices).ok());
    EXPECT_EQ(encoder.zeroCopy, EncoderZeroCopy::Off);
    EXPECT_EQ(notices, (std::vector<std::string>{
                           "encoder: copying (zero_copy \"auto\"): /dev/video10 already takes the camera's buffers"}));
    encoder.zeroCopy = EncoderZeroCopy::On;
    auto refused = limitEncoderZeroCopy({output}, encoder, notices);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::ConfigError);
    output.zeroCopy = ZeroCopy::Off; // an output that copies leaves the buffers to the encoder
    ASSERT_TRUE(limitEncoderZeroCopy({output}, encoder, notices).ok());
    EXPECT_EQ(encoder.zeroCopy, EncoderZeroCopy::On);
}

TEST(ZeroCopyConfig, TheEncodersOnNeedsAV4l2Encoder)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs: [encoder] itself is refused (config.StreamConfig)";
    std::vector<ConfigProblem> problems;
    (void)loadText("[encoder]\nencoder = \"openh264\"\nzero_copy = \"on\"\n[[sink]]\nkind = \"file\"\n"
                   "path = \"/tmp/zero.h264\"\n",
                   problems);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].format(), "zero.toml:3:13: encoder.zero_copy: \"on\" needs encoder = \"v4l2\": only a V4L2 "
                                    "M2M encoder imports the capture buffers (DMABUF), not encoder = \"openh264\"");
}

} // namespace
} // namespace overlayd
