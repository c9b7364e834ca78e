// SPDX-License-Identifier: Apache-2.0
// Capture streaming: leases give buffers back, sequence gaps count as drops, timestamps and colorimetry kept,
// stop() frees everything and start() works again.
#include <gtest/gtest.h>

#include "test_devices.h"

namespace overlayd::test {
namespace {

using std::chrono::microseconds;

struct Streaming : ::testing::Test {
    CaptureRig rig;
    FakeDevice *device = nullptr;

    void SetUp() override
    {
        device = &addYuyvCamera(rig.kernel);
        rig.make(captureOptions("YUYV", 640, 480, 30.0));
        auto format = rig.source->start();
        ASSERT_TRUE(format.ok()) << format.error().message;
    }
};

TEST_F(Streaming, StartQueuesEveryBufferAndStreams)
{
    EXPECT_TRUE(device->streaming);
    EXPECT_EQ(device->buffers.size(), 4u);
    EXPECT_EQ(device->queued.size(), 4u);
    EXPECT_EQ(rig.source->eventFd() >= 0, true);
    EXPECT_EQ(rig.kernel.mappings(), 4u);
}

TEST_F(Streaming, DestroyingTheLeaseRequeuesItsBuffer)
{
    ASSERT_TRUE(device->produce(0, microseconds(0)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    EXPECT_EQ(device->queued.size(), 3u);
    const unsigned qbufsBefore = device->qbufCalls;
    EXPECT_FALSE(device->buffers[0].queued);
    lease->reset();
    EXPECT_EQ(device->qbufCalls, qbufsBefore + 1);
    EXPECT_TRUE(device->buffers[0].queued);
    EXPECT_EQ(device->queued.size(), 4u);
    EXPECT_EQ(device->queued.back(), 0u);
}

TEST_F(Streaming, LeaseViewsTheDriversBuffer)
{
    ASSERT_TRUE(device->produce(0, microseconds(0), [](FakeDevice::Buffer &b) { b.planes[0][1281] = 77; }));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok());
    EXPECT_EQ(lease->view().planes[0].data, device->buffers[0].planes[0].data());
    EXPECT_EQ(lease->view().planes[0].stride, 1280u);
    EXPECT_EQ(lease->view().planes[0].data[1281], 77); // row 1, byte 1
}

TEST_F(Streaming, SequenceGapsCountAsDropsAndTimestampsAreKept)
{
    const uint32_t sequences[] = {10, 11, 14, 15, 20};
    const uint64_t expected[] = {0, 1, 4, 5, 10};
    for (unsigned i = 0; i < 5; ++i) {
        ASSERT_TRUE(device->produce(sequences[i], microseconds(12'345'678 + i)));
        auto lease = rig.source->nextFrame();
        ASSERT_TRUE(lease.ok()) << lease.error().message;
        EXPECT_EQ(lease->metadata().sequence, expected[i]);
        EXPECT_EQ(lease->metadata().timestamp.count(), 12'345'678'000 + i * 1000);
    }
    EXPECT_EQ(rig.source->droppedFrames(), 2u + 4u);
}

TEST_F(Streaming, SequenceCounterWrapIsNotADrop)
{
    for (uint32_t sequence : {0xfffffffeu, 0xffffffffu, 0u, 1u}) {
        ASSERT_TRUE(device->produce(sequence, microseconds(0)));
        ASSERT_TRUE(rig.source->nextFrame().ok());
    }
    EXPECT_EQ(rig.source->droppedFrames(), 0u);
}

TEST_F(Streaming, CorruptFrameIsSkippedRequeuedAndCounted)
{
    ASSERT_TRUE(device->produce(0, microseconds(0), {}, V4L2_BUF_FLAG_ERROR));
    auto lease = rig.source->nextFrame();
    ASSERT_FALSE(lease.ok());
    EXPECT_EQ(lease.error().code, ErrorCode::TryAgain);
    EXPECT_EQ(device->queued.size(), 4u);
    EXPECT_EQ(rig.source->droppedFrames(), 1u);
}

TEST_F(Streaming, StopFreesEverythingAndStartWorksAgain)
{
    ASSERT_TRUE(device->produce(0, microseconds(0)));
    auto held = rig.source->nextFrame(); // a lease still out at stop()
    ASSERT_TRUE(held.ok());
    rig.source->stop();
    EXPECT_FALSE(device->streaming);
    EXPECT_EQ(rig.kernel.mappings(), 0u);
    EXPECT_EQ(device->reqbufsZero, 1u);
    EXPECT_EQ(rig.kernel.openFds(), 0u);
    EXPECT_EQ(rig.source->eventFd(), -1);
    const unsigned qbufs = device->qbufCalls;
    held->reset(); // after stop() the give-back does nothing
    EXPECT_EQ(device->qbufCalls, qbufs);

    auto again = rig.source->start();
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_TRUE(device->streaming);
    ASSERT_TRUE(device->produce(500, microseconds(1)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    EXPECT_EQ(lease->metadata().sequence, 0u); // counts from 0 again
    EXPECT_EQ(rig.source->droppedFrames(), 0u);
}

TEST(V4l2Colorimetry, FromTheDriverUnlessConfigured)
{
    CaptureRig rig;
    FakeDevice &device = addYuyvCamera(rig.kernel);
    device.colorspace = V4L2_COLORSPACE_REC709; // ycbcr_enc and quantization DEFAULT: BT.709 limited
    rig.make(captureOptions("YUYV", 640, 480, 30.0));
    auto format = rig.source->start();
    ASSERT_TRUE(format.ok());
    EXPECT_EQ(format->colorimetry, (Colorimetry{YcbcrMatrix::Bt709, ColourRange::Limited}));
    ASSERT_TRUE(device.produce(0, microseconds(0)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok());
    EXPECT_EQ(lease->metadata().colorimetry, (Colorimetry{YcbcrMatrix::Bt709, ColourRange::Limited}));
    lease->reset();
    rig.source->stop();

    device.quantization = V4L2_QUANTIZATION_FULL_RANGE;
    EXPECT_EQ(rig.source->start()->colorimetry, (Colorimetry{YcbcrMatrix::Bt709, ColourRange::Full}));
    rig.source->stop();

    auto options = captureOptions("YUYV", 640, 480, 30.0);
    options.colorimetry = Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full};
    rig.make(options);
    EXPECT_EQ(rig.source->start()->colorimetry, (Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full}));
}

TEST(V4l2MultiPlanarCapture, StreamsThroughTheMplaneApi)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    device.formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}}, {30.0}}};
    rig.make(captureOptions("YUYV", 640, 480, 30.0));
    ASSERT_TRUE(rig.source->start().ok());
    for (uint32_t sequence = 0; sequence < 10; ++sequence) {
        ASSERT_TRUE(device.produce(sequence, microseconds(sequence)));
        auto lease = rig.source->nextFrame(); // the fake refuses an mplane DQBUF/QBUF without its plane array
        ASSERT_TRUE(lease.ok()) << lease.error().message;
        EXPECT_EQ(lease->metadata().sequence, sequence);
    }
    EXPECT_EQ(device.queued.size(), 4u);
}

} // namespace
} // namespace overlayd::test
