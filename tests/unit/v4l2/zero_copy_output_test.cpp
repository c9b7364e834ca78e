// SPDX-License-Identifier: Apache-2.0
// Zero copy, output side: the choice at open (auto, on, off), capture buffers queued by DMABUF and held until the
// output returns them, frames of our own, refusals and a vanished output.
#include <gtest/gtest.h>

#include <algorithm>

#include "media/frame_buffer.h"
#include "zero_copy_rig.h"

namespace overlayd::test {
namespace {

struct ZeroCopyOutput : ZeroCopyRig, ::testing::Test {};

TEST_F(ZeroCopyOutput, AutoCopiesWhenTheOutputRefusesDmabuf)
{
    output->importsDmabuf = false;
    startCapture();
    auto opened = openSink(ZeroCopy::Auto);
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    EXPECT_FALSE(sink->zeroCopy());
    ASSERT_EQ(sinkLog.size(), 1u);
    EXPECT_EQ(sinkLog[0], "v4l2 output /dev/video10 (Out): copying frames (no zero copy: /dev/video10 (Out): "
                          "VIDIOC_REQBUFS 2 DMABUF buffers failed: Invalid argument)");
    auto lease = capture(0, 42);
    EXPECT_FALSE(sink->takesLease(lease->view()));
    ASSERT_TRUE(sink->write(lease->view(), lease->metadata()).ok());
    ASSERT_EQ(output->written.size(), 1u);
    EXPECT_EQ(output->written[0][0][1000], 42);
}

TEST_F(ZeroCopyOutput, OnFailsAtOpenWithTheReason)
{
    output->importsDmabuf = false;
    startCapture();
    auto refused = openSink(ZeroCopy::On);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::ConfigError);
    EXPECT_EQ(refused.error().message, "v4l2 output /dev/video10 (Out): zero_copy = \"on\" is impossible: "
                                       "/dev/video10 (Out): VIDIOC_REQBUFS 2 DMABUF buffers failed: Invalid argument");

    output->importsDmabuf = true;
    rig.source->stop();
    startCapture(false);
    refused = openSink(ZeroCopy::On);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("the frames carry no dmabuf fds"), std::string::npos)
        << refused.error().message;
}

TEST_F(ZeroCopyOutput, OnRefusesAStrideTheOutputCannotRead)
{
    camera->padding = {32, 0, 0};
    startCapture();
    auto refused = openSink(ZeroCopy::On);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("the output's bytesperline 1280 differs from the capture's 1312"),
              std::string::npos)
        << refused.error().message;
}

TEST_F(ZeroCopyOutput, OffCopiesWithoutAsking)
{
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::Off).ok());
    EXPECT_FALSE(sink->zeroCopy());
    EXPECT_TRUE(sinkLog.empty());
    EXPECT_FALSE(sink->takesLease(capture(0, 1)->view()));
}

TEST_F(ZeroCopyOutput, LeaseIsHeldUntilTheOutputReturnsTheBufferThenGivenBack)
{
    output->consumeOutput = false;
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::On).ok());
    EXPECT_TRUE(sink->zeroCopy());
    auto first = capture(0, 7);
    const int fd = first->view().planes[0].dmabufFd;
    ASSERT_TRUE(sink->takesLease(first->view()));
    ASSERT_TRUE(sink->writeLease(std::move(first)).ok());
    EXPECT_EQ(camera->queued.size(), 3u); // capture buffer 0 is the output's now
    EXPECT_FALSE(camera->buffers[0].queued);
    ASSERT_EQ(output->queued.size(), 1u);
    EXPECT_EQ(output->buffers[output->queued[0]].dmabufFds[0], fd);
    EXPECT_EQ(sink->heldLeases(), 1u);

    ASSERT_TRUE(output->consume()); // the device read it: the capture's own bytes, no copy
    ASSERT_EQ(output->written.size(), 1u);
    EXPECT_EQ(output->written[0][0].size(), 640u * 2 * 480);
    EXPECT_EQ(output->written[0][0][5000], 7);
    EXPECT_FALSE(camera->buffers[0].queued); // not given back before VIDIOC_DQBUF says so

    ASSERT_TRUE(sink->writeLease(capture(1, 8)).ok()); // reclaims first
    EXPECT_TRUE(camera->buffers[0].queued);
    EXPECT_EQ(sink->heldLeases(), 1u);
    EXPECT_EQ(sink->zeroCopiedFrames(), 2u);
}

TEST_F(ZeroCopyOutput, TheCaptureKeepsTwoBuffersTheOutputMayNotHold)
{
    output->consumeOutput = false;
    startCapture(); // 4 capture buffers: the output may hold 2
    ASSERT_TRUE(openSink(ZeroCopy::Auto, 8).ok());
    ASSERT_TRUE(sink->writeLease(capture(0, 1)).ok());
    ASSERT_TRUE(sink->writeLease(capture(1, 2)).ok());
    ASSERT_TRUE(sink->writeLease(capture(2, 3)).ok());
    EXPECT_EQ(sink->heldLeases(), 2u);
    EXPECT_EQ(sink->droppedFrames(), 1u);
    EXPECT_EQ(camera->queued.size(), 2u); // the dropped frame's buffer went straight back
}

TEST_F(ZeroCopyOutput, OwnFramesSwitchTheQueueToMmapAndLeasesSwitchItBack)
{
    output->consumeOutput = false;
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::On).ok());
    ASSERT_TRUE(sink->writeLease(capture(0, 1)).ok());
    auto noSignal = FrameBuffer::allocate(stream);
    std::fill(noSignal->data(), noSignal->data() + noSignal->size(), 57);
    ASSERT_TRUE(sink->write(noSignal->view(), {}).ok());
    EXPECT_EQ(sink->heldLeases(), 0u); // streaming off returned every buffer: the capture has all 4 again
    EXPECT_EQ(camera->queued.size(), 4u);
    EXPECT_EQ(output->memory, uint32_t(V4L2_MEMORY_MMAP));
    ASSERT_TRUE(output->consume());
    EXPECT_EQ(output->written.back()[0][640], 57);
    ASSERT_TRUE(sink->writeLease(capture(1, 2)).ok());
    EXPECT_EQ(output->memory, uint32_t(V4L2_MEMORY_DMABUF));
    EXPECT_TRUE(output->streaming);
    EXPECT_EQ(sink->zeroCopiedFrames(), 2u);
    EXPECT_EQ(sink->writtenFrames(), 3u);
}

TEST_F(ZeroCopyOutput, MultiPlanarCaptureToMultiPlanarOutputQueuesAnFdPerPlane)
{
    camera->bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    camera->formats = {{V4L2_PIX_FMT_NV12M, {{640, 480}}, {30.0}}};
    output->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
    output->formats = {{V4L2_PIX_FMT_NV12M, {{640, 480}}, {30.0}}};
    startCapture(true, "NV12");
    ASSERT_TRUE(openSink(ZeroCopy::On).ok());
    auto lease = capture(0, 5);
    const int luma = lease->view().planes[0].dmabufFd, chroma = lease->view().planes[1].dmabufFd;
    ASSERT_TRUE(sink->takesLease(lease->view()));
    ASSERT_TRUE(sink->writeLease(std::move(lease)).ok());
    const FakeDevice::Buffer &queued = output->buffers[0];
    EXPECT_EQ(queued.dmabufFds[0], luma);
    EXPECT_EQ(queued.dmabufFds[1], chroma);
    ASSERT_EQ(output->written.size(), 1u);
    EXPECT_EQ(output->written[0][0].size(), 640u * 480);
    EXPECT_EQ(output->written[0][1].size(), 640u * 240);
}

TEST_F(ZeroCopyOutput, MultiPlanarDataOffsetIsPassedOnAndCountedInBytesUsed)
{
    camera->bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    camera->formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}}, {30.0}}};
    output->bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
    camera->dataOffset = {256, 0, 0};
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::On).ok());
    auto lease = capture(0, 5);
    camera->buffers[0].planes[0][255] = 99; // the header's last byte: the output must not read it
    ASSERT_TRUE(sink->takesLease(lease->view()));
    ASSERT_TRUE(sink->writeLease(std::move(lease)).ok());
    EXPECT_EQ(output->buffers[0].dataOffset[0], 256u);
    EXPECT_EQ(output->buffers[0].bytesUsed[0], 256u + 640 * 2 * 480);
    ASSERT_EQ(output->written.size(), 1u);
    EXPECT_EQ(output->written[0][0].size(), 640u * 2 * 480);
    EXPECT_EQ(output->written[0][0][0], 5);
}

TEST_F(ZeroCopyOutput, AutoStopsZeroCopyWhenTheDriverRefusesAQueuedDmabuf)
{
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::Auto).ok());
    output->qbufError = -EINVAL;
    auto status = sink->writeLease(capture(0, 1));
    ASSERT_FALSE(status.ok());
    EXPECT_FALSE(sink->zeroCopy());
    EXPECT_EQ(sinkLog.back(), "v4l2 output /dev/video10 (Out): the driver refused a DMABUF buffer (/dev/video10 "
                              "(Out): VIDIOC_QBUF 0 (DMABUF) failed: Invalid argument); copying frames from now on");
    EXPECT_EQ(camera->queued.size(), 4u); // the lease went back
}

TEST_F(ZeroCopyOutput, VanishedOutputIsDeviceLostAndGivesEveryLeaseBack)
{
    output->consumeOutput = false;
    startCapture();
    ASSERT_TRUE(openSink(ZeroCopy::On).ok());
    ASSERT_TRUE(sink->writeLease(capture(0, 1)).ok());
    output->dqbufErrors = {-ENODEV};
    auto status = sink->writeLease(capture(1, 2));
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::DeviceLost);
    EXPECT_EQ(sink->heldLeases(), 0u);
    EXPECT_EQ(camera->queued.size(), 4u);
    ASSERT_TRUE(sink->close().ok());
    EXPECT_EQ(sinkLog.back(), "v4l2 output /dev/video10 (Out): 1 frames out: 1 zero-copy, 0 copied, 0 dropped");
}

} // namespace
} // namespace overlayd::test
