// SPDX-License-Identifier: Apache-2.0
// EncodedStream behind a fake engine: the pipeline's sink opens the engine for the stream (I420 of its size),
// writes inline, hands the engine frames that are released when it lets go, and closes it.
#include <gtest/gtest.h>

#include "fake_stream_engine.h"
#include "media/frame_buffer.h"
#include "stream/encoded_stream.h"

using namespace overlayd;

namespace {

TEST(EncodedStream, TheSinkFeedsTheEngineThroughBoundedSlots)
{
    test::FakeStreamEngine::Calls calls;
    StreamOptions options;
    options.encoder.queuedFrames = 2;
    options.sinks.push_back({EncodedSinkKind::Rtsp, "sink[0]", {}, {}, {}, {}});
    auto stream = std::make_shared<EncodedStream>(options, std::make_unique<test::FakeStreamEngine>(calls));
    std::unique_ptr<FrameSink> sink = stream->sink();
    EXPECT_TRUE(sink->writesInline());

    StreamFormat format;
    format.format = pixelFormatFromName("NV12");
    format.width = 16, format.height = 8, format.fps = 25;
    ASSERT_TRUE(sink->open(format));
    EXPECT_EQ(calls.opens, 1u);
    EXPECT_EQ(calls.format, (EngineFormat{16, 8, 25, false, {}}));

    FrameBuffer frame = std::move(*FrameBuffer::allocate(format));
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(sink->write(frame.view(), {}));
    EXPECT_EQ(calls.pushed, 2u); // the third found both slots with the engine
    EncodedStreamState state = stream->state();
    EXPECT_EQ(state.feed.dropped, 1u);
    EXPECT_EQ(state.feed.converted, 2u); // NV12 to I420, once per frame
    EXPECT_EQ(state.engine.encoder, "fake");

    calls.held.clear(); // the engine lets go of both
    EXPECT_EQ(stream->state().feed.inFlight, 0u);
    ASSERT_TRUE(sink->write(frame.view(), {}));
    EXPECT_EQ(calls.pushed, 3u);

    ASSERT_TRUE(sink->close());
    EXPECT_EQ(calls.closes, 1u);
    EXPECT_TRUE(calls.held.empty());
    EXPECT_FALSE(sink->write(frame.view(), {})); // closed: refused, not crashed
}

TEST(EncodedStream, DescribesTheEncoderAndItsSinks)
{
    test::FakeStreamEngine::Calls calls;
    StreamOptions options;
    options.encoder.kind = EncoderKind::OpenH264;
    EncodedSinkOptions rtsp;
    rtsp.key = "sink[0]";
    rtsp.rtsp.listen = "127.0.0.1:8554";
    rtsp.rtsp.path = "/cam";
    options.sinks.push_back(rtsp);
    EncodedStream stream(options, std::make_unique<test::FakeStreamEngine>(calls));
    EXPECT_EQ(stream.describe(), "h264 (openh264) -> rtsp://127.0.0.1:8554/cam");
}

} // namespace
