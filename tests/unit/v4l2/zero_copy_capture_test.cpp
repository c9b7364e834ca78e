// SPDX-License-Identifier: Apache-2.0
// Zero copy, capture side: VIDIOC_EXPBUF on request, the fd and offset of every plane, and leases given back
// from any thread, keeping their fds open after stop().
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "zero_copy_rig.h"

namespace overlayd::test {
namespace {

struct ZeroCopyCapture : ZeroCopyRig, ::testing::Test {};

TEST_F(ZeroCopyCapture, CaptureExportsOnlyWhenAsked)
{
    startCapture(false);
    EXPECT_EQ(stream.dmabufBuffers, 0u);
    EXPECT_EQ(capture(0, 1)->view().planes[0].dmabufFd, -1);
    EXPECT_EQ(rig.kernel.openDmabufs(), 0u);
}

TEST_F(ZeroCopyCapture, ExportedLeasesCarryOneFdPerBufferUntilTheLastLeaseIsGone)
{
    startCapture();
    EXPECT_EQ(stream.dmabufBuffers, 4u);
    EXPECT_EQ(rig.kernel.openDmabufs(), 4u);
    std::vector<int> fds;
    std::vector<std::shared_ptr<const FrameLease>> held;
    for (uint32_t i = 0; i < 3; ++i) {
        held.push_back(capture(i, uint8_t(i)));
        EXPECT_EQ(held.back()->view().planes[0].dmabufOffset, 0u);
        fds.push_back(held.back()->view().planes[0].dmabufFd);
    }
    std::sort(fds.begin(), fds.end());
    EXPECT_TRUE(fds[0] >= 0 && std::adjacent_find(fds.begin(), fds.end()) == fds.end());
    rig.source->stop(); // the leases still out keep the fds open (a sink may be about to queue them)
    EXPECT_EQ(rig.kernel.openDmabufs(), 4u);
    held.clear();
    EXPECT_EQ(rig.kernel.openDmabufs(), 0u);
    EXPECT_EQ(rig.kernel.openFds(), 0u);
}

TEST_F(ZeroCopyCapture, RefusedExportIsLoggedOnceAndStreamsWithoutFds)
{
    camera->expbufError = -EINVAL;
    startCapture();
    EXPECT_EQ(stream.dmabufBuffers, 0u);
    EXPECT_EQ(capture(0, 1)->view().planes[0].dmabufFd, -1);
    ASSERT_TRUE(rig.source->start().ok());
    ASSERT_EQ(rig.log.size(), 1u);
    EXPECT_EQ(rig.log[0], "/dev/video0 (Fake Cam): VIDIOC_EXPBUF buffer 0 plane 0 failed: Invalid argument: buffers "
                          "not exportable, frames carry no dmabuf fds");
}

TEST_F(ZeroCopyCapture, SinglePlanarNv12SharesOneFdWithTheChromaAtItsOffset)
{
    camera->formats = {{V4L2_PIX_FMT_NV12, {{640, 480}}, {30.0}}};
    camera->padding = {64, 0, 0};
    startCapture(true, "NV12");
    auto lease = capture(0, 9);
    const FrameView &view = lease->view();
    EXPECT_EQ(view.planes[1].dmabufFd, view.planes[0].dmabufFd);
    EXPECT_EQ(view.planes[1].dmabufOffset, 704u * 480); // bytesperline 704, 480 luma rows
}

TEST_F(ZeroCopyCapture, MultiPlanarNv12mHasAnFdPerPlaneAndDataOffsetsCount)
{
    camera->bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    camera->formats = {{V4L2_PIX_FMT_NV12M, {{640, 480}}, {30.0}}};
    camera->dataOffset = {128, 0, 0};
    startCapture(true, "NV12");
    auto lease = capture(0, 9);
    EXPECT_EQ(lease->view().planes[0].data, camera->buffers[0].planes[0].data() + 128);
    const FrameView &view = lease->view();
    EXPECT_NE(view.planes[1].dmabufFd, view.planes[0].dmabufFd);
    EXPECT_EQ(view.planes[0].dmabufOffset, 128u);
    EXPECT_EQ(view.planes[1].dmabufOffset, 0u);
}

TEST_F(ZeroCopyCapture, LeaseGivenBackOnAnotherThreadRequeuesAndAfterStopDoesNothing)
{
    startCapture();
    auto lease = capture(0, 1);
    std::thread([&lease] { lease.reset(); }).join();
    EXPECT_EQ(camera->queued.size(), 4u);
    lease = capture(1, 2);
    rig.source->stop();
    const unsigned qbufs = camera->qbufCalls;
    std::thread([&lease] { lease.reset(); }).join();
    EXPECT_EQ(camera->qbufCalls, qbufs);
    EXPECT_EQ(rig.kernel.openFds(), 0u);
}

} // namespace
} // namespace overlayd::test
