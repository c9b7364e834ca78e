// SPDX-License-Identifier: Apache-2.0
// Zero copy to the encoder behind a fake engine: an I420 capture buffer with a DMABUF goes to a V4L2 encoder as
// that DMABUF (no bytes, the planes' offsets and strides), the lease goes back to the source only when the encoder
// lets the frame go, at most the buffers the capture can spare are held, and the counters say zero-copy, not
// copied; zero_copy = "on" refuses the start where it is impossible, with the reason, and "off" or a software
// encoder keep the copy.
#include <gtest/gtest.h>

#include "fake_stream_engine.h"
#include "media/frame_buffer.h"
#include "stream/encoded_stream.h"

using namespace overlayd;

namespace {

constexpr int kFd = 42; // the fake engine never touches it

StreamFormat captureFormat(const char *pixelFormat, unsigned dmabufBuffers)
{
    StreamFormat format;
    format.format = pixelFormatFromName(pixelFormat);
    format.width = 16, format.height = 8, format.fps = 25;
    format.dmabufBuffers = dmabufBuffers;
    return format;
}

struct Capture {
    StreamFormat format;
    FrameBuffer buffer;
    unsigned givenBack = 0;

    Capture(const char *pixelFormat, unsigned dmabufBuffers)
        : format(captureFormat(pixelFormat, dmabufBuffers)), buffer(std::move(*FrameBuffer::allocate(format)))
    {}
    // A lease of the buffer as a V4L2 capture exports it: every plane in one DMABUF, at its offset in it.
    std::shared_ptr<const FrameLease> lease(uint64_t sequence)
    {
        FrameView view = buffer.view();
        for (unsigned p = 0; p < 3; ++p) {
            view.planes[p].dmabufFd = kFd;
            view.planes[p].dmabufOffset = size_t(view.planes[p].data - view.planes[0].data);
        }
        FrameMetadata metadata;
        metadata.sequence = sequence;
        return std::make_shared<const FrameLease>(view, metadata, [this] { ++givenBack; });
    }
};

std::shared_ptr<EncodedStream> makeStream(test::FakeStreamEngine::Calls &calls, EncoderZeroCopy zeroCopy)
{
    StreamOptions options;
    options.encoder.kind = EncoderKind::V4l2;
    options.encoder.queuedFrames = 3;
    options.encoder.zeroCopy = zeroCopy;
    options.sinks.push_back({EncodedSinkKind::File, "sink[0]", {}, {}, {}, {}});
    return std::make_shared<EncodedStream>(options, std::make_unique<test::FakeStreamEngine>(calls));
}

TEST(EncoderZeroCopy, TheCaptureBufferGoesToTheEncoderByItsDmabuf)
{
    test::FakeStreamEngine::Calls calls;
    calls.importsDmabuf = true;
    auto stream = makeStream(calls, EncoderZeroCopy::Auto);
    std::unique_ptr<FrameSink> sink = stream->sink();
    Capture capture("YUV420", 4); // the capture keeps 2: the encoder may hold 2, fewer than its queue of 3
    ASSERT_TRUE(sink->open(capture.format));
    EXPECT_TRUE(calls.format.dmabuf);

    auto first = capture.lease(1);
    ASSERT_TRUE(sink->takesLease(first->view()));
    ASSERT_TRUE(sink->writeLease(first));
    ASSERT_EQ(calls.held.size(), 1u);
    const EncoderInput &input = calls.held[0];
    EXPECT_EQ(input.data, nullptr); // no bytes: the DMABUF
    EXPECT_EQ(input.dmabuf.fd, kFd);
    EXPECT_EQ(input.sequence, 1u);
    // I420 16x8 packed: Y at 0 (stride 16), U at 128, V at 160 (stride 8 each)
    EXPECT_EQ(input.dmabuf.offsets[0], 0u);
    EXPECT_EQ(input.dmabuf.offsets[1], 128u);
    EXPECT_EQ(input.dmabuf.offsets[2], 160u);
    EXPECT_EQ(input.dmabuf.strides[0], 16u);
    EXPECT_EQ(input.dmabuf.strides[1], 8u);
    EXPECT_EQ(input.dmabuf.strides[2], 8u);
    first.reset(); // the pipeline lets go: the encoder's reference keeps the buffer from the source
    EXPECT_EQ(capture.givenBack, 0u);

    ASSERT_TRUE(sink->writeLease(capture.lease(2)));
    ASSERT_TRUE(sink->writeLease(capture.lease(3))); // a third: the capture would be left one buffer
    EXPECT_EQ(calls.pushed, 2u);
    EXPECT_EQ(capture.givenBack, 1u); // the dropped one went straight back
    EncodedStreamState state = stream->state();
    EXPECT_EQ(state.feed.zeroCopy, 2u);
    EXPECT_EQ(state.feed.copied, 0u);
    EXPECT_EQ(state.feed.dropped, 1u);

    calls.held.clear(); // the encoder lets go of both
    EXPECT_EQ(capture.givenBack, 3u);
    EXPECT_EQ(stream->state().feed.inFlight, 0u);
    ASSERT_TRUE(sink->close());
}

TEST(EncoderZeroCopy, OtherFramesAndEncodersAreCopied)
{
    { // a software encoder: the engine does not import, the frame is copied
        test::FakeStreamEngine::Calls calls;
        auto stream = makeStream(calls, EncoderZeroCopy::Auto);
        Capture capture("YUV420", 4);
        ASSERT_TRUE(stream->open(capture.format));
        EXPECT_FALSE(stream->takesLease(capture.lease(1)->view()));
    }
    { // "off"
        test::FakeStreamEngine::Calls calls;
        calls.importsDmabuf = true;
        auto stream = makeStream(calls, EncoderZeroCopy::Off);
        Capture capture("YUV420", 4);
        ASSERT_TRUE(stream->open(capture.format));
        EXPECT_FALSE(calls.format.dmabuf);
        EXPECT_FALSE(stream->takesLease(capture.lease(1)->view()));
    }
    { // a frame without a DMABUF
        test::FakeStreamEngine::Calls calls;
        calls.importsDmabuf = true;
        auto stream = makeStream(calls, EncoderZeroCopy::Auto);
        Capture capture("YUV420", 4);
        ASSERT_TRUE(stream->open(capture.format));
        EXPECT_FALSE(stream->takesLease(capture.buffer.view()));
        ASSERT_TRUE(stream->write(capture.buffer.view(), {}));
        EXPECT_EQ(stream->state().feed.copied, 1u);
    }
}

TEST(EncoderZeroCopy, OnRefusesTheStartWhereItIsImpossible)
{
    const auto refusal = [](const char *pixelFormat, unsigned dmabufBuffers, bool imports) {
        test::FakeStreamEngine::Calls calls;
        calls.importsDmabuf = imports;
        auto stream = makeStream(calls, EncoderZeroCopy::On);
        Capture capture(pixelFormat, dmabufBuffers);
        const Status opened = stream->open(capture.format);
        return opened ? std::string("opened") : opened.error().message;
    };
    EXPECT_EQ(refusal("YUV420", 4, true), "opened");
    EXPECT_NE(refusal("YUV420", 0, true).find("the source exports no DMABUF buffers"), std::string::npos);
    EXPECT_NE(refusal("NV12", 4, true).find("the encoder imports I420 frames"), std::string::npos);
    EXPECT_NE(refusal("YUV420", 4, false).find("the encoder fake is not a V4L2 M2M encoder"), std::string::npos);
}

} // namespace
