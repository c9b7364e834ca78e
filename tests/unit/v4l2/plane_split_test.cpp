// SPDX-License-Identifier: Apache-2.0
// Plane splitting: per-plane strides from the driver, a single-plane buffer holding NV12/YUV420 split once.
#include <gtest/gtest.h>

#include "drivers/v4l2/frame_split.h"
#include "test_devices.h"

namespace overlayd::test {
namespace {

// Starts a capture of `format` 640x480 on a fake with the given per-plane bytesperline padding.
FrameLease captureOne(CaptureRig &rig, uint32_t bufferType, uint32_t fourcc, const std::string &name,
                      std::array<unsigned, 3> padding, FakeDevice **deviceOut = nullptr)
{
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.bufferType = bufferType;
    device.formats = {{fourcc, {{640, 480}}, {30.0}}};
    device.padding = padding;
    if (deviceOut)
        *deviceOut = &device;
    rig.make(captureOptions(name, 640, 480, 30.0));
    auto format = rig.source->start();
    EXPECT_TRUE(format.ok()) << format.error().message;
    EXPECT_TRUE(device.produce(0, std::chrono::microseconds(0)));
    auto lease = rig.source->nextFrame();
    EXPECT_TRUE(lease.ok()) << lease.error().message;
    return lease.ok() ? std::move(lease.value()) : FrameLease();
}

TEST(V4l2PlaneSplit, SinglePlaneNv12WithPaddedBytesPerLine)
{
    CaptureRig rig;
    FakeDevice *device = nullptr;
    FrameLease lease = captureOne(rig, V4L2_BUF_TYPE_VIDEO_CAPTURE, V4L2_PIX_FMT_NV12, "NV12", {64, 0, 0}, &device);
    const FrameView &view = lease.view();
    const uint8_t *base = device->buffers[0].planes[0].data();
    // bytesperline 704: Y is 704 * 480 bytes, then CbCr rows of 704 bytes (hand-computed, not from the table).
    EXPECT_EQ(view.planes[0].data, base);
    EXPECT_EQ(view.planes[0].stride, 704u);
    EXPECT_EQ(view.planes[1].data, base + 704 * 480);
    EXPECT_EQ(view.planes[1].stride, 704u);
    EXPECT_EQ(view.planes[1].size, 704u * 240);
}

TEST(V4l2PlaneSplit, SinglePlaneYuv420HalvesTheChromaStride)
{
    CaptureRig rig;
    FakeDevice *device = nullptr;
    FrameLease lease = captureOne(rig, V4L2_BUF_TYPE_VIDEO_CAPTURE, V4L2_PIX_FMT_YUV420, "YUV420", {64, 0, 0}, &device);
    const FrameView &view = lease.view();
    const uint8_t *base = device->buffers[0].planes[0].data();
    EXPECT_EQ(view.planes[1].data, base + 704 * 480); // Cb
    EXPECT_EQ(view.planes[1].stride, 352u);
    EXPECT_EQ(view.planes[2].data, base + 704 * 480 + 352 * 240); // Cr
    EXPECT_EQ(view.planes[2].stride, 352u);
}

TEST(V4l2PlaneSplit, MultiPlanarNv12mKeepsEachPlanesOwnBytesPerLine)
{
    CaptureRig rig;
    FakeDevice *device = nullptr;
    FrameLease lease =
        captureOne(rig, V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE, V4L2_PIX_FMT_NV12M, "NV12", {32, 96, 0}, &device);
    const FrameView &view = lease.view();
    EXPECT_EQ(view.format->name, "NV12");
    EXPECT_EQ(view.planes[0].data, device->buffers[0].planes[0].data());
    EXPECT_EQ(view.planes[0].stride, 672u);
    EXPECT_EQ(view.planes[1].data, device->buffers[0].planes[1].data()); // its own buffer
    EXPECT_EQ(view.planes[1].stride, 736u);
}

TEST(V4l2PlaneSplit, MultiPlanarApiWithOneMemoryPlaneIsSplitLikeSinglePlanar)
{
    CaptureRig rig;
    FakeDevice *device = nullptr;
    FrameLease lease =
        captureOne(rig, V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE, V4L2_PIX_FMT_NV12, "NV12", {128, 0, 0}, &device);
    const FrameView &view = lease.view();
    const uint8_t *base = device->buffers[0].planes[0].data();
    EXPECT_EQ(view.planes[1].data, base + 768 * 480);
    EXPECT_EQ(view.planes[1].stride, 768u);
}

TEST(V4l2PlaneSplit, DataOffsetOfAMemoryPlaneIsSkipped)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    device.formats = {{V4L2_PIX_FMT_NV16M, {{640, 480}}, {30.0}}};
    device.padding = {128, 0, 0}; // room for the header, as vivid sizes its NV16M plane 0
    device.dataOffset = {128, 0, 0};
    rig.make(captureOptions("NV16", 640, 480, 30.0));
    ASSERT_TRUE(rig.source->start().ok());
    ASSERT_TRUE(device.produce(0, std::chrono::microseconds(0)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    EXPECT_EQ(lease->view().planes[0].data, device.buffers[0].planes[0].data() + 128);
    EXPECT_EQ(lease->view().planes[1].data, device.buffers[0].planes[1].data());
}

TEST(V4l2PlaneSplit, DataOffsetOfASingleMemoryPlaneShiftsEveryPlane)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    device.formats = {{V4L2_PIX_FMT_NV12, {{64, 32}}, {30.0}}};
    device.dataOffset = {64, 0, 0};
    rig.make(captureOptions("NV12", 64, 32, 30.0));
    ASSERT_TRUE(rig.source->start().ok());
    ASSERT_TRUE(device.produce(0, std::chrono::microseconds(0)));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok()) << lease.error().message;
    EXPECT_EQ(lease->view().planes[0].data, device.buffers[0].planes[0].data() + 64);
    EXPECT_EQ(lease->view().planes[1].data, device.buffers[0].planes[0].data() + 64 + 64 * 32);
}

TEST(V4l2PlaneSplit, PixelsAreReadThroughTheStrides)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.formats = {{V4L2_PIX_FMT_NV12, {{64, 32}}, {30.0}}};
    device.padding = {16, 0, 0};
    rig.make(captureOptions("NV12", 64, 32, 30.0));
    ASSERT_TRUE(rig.source->start().ok());
    // Luma (x, y) = x + y, CbCr pair (i, j) = (100 + i, 200 - j), written at offsets computed by hand.
    ASSERT_TRUE(device.produce(0, std::chrono::microseconds(0), [](FakeDevice::Buffer &b) {
        for (unsigned y = 0; y < 32; ++y)
            for (unsigned x = 0; x < 64; ++x)
                b.planes[0][y * 80 + x] = uint8_t(x + y);
        for (unsigned j = 0; j < 16; ++j)
            for (unsigned i = 0; i < 32; ++i) {
                b.planes[0][80 * 32 + j * 80 + 2 * i] = uint8_t(100 + i);
                b.planes[0][80 * 32 + j * 80 + 2 * i + 1] = uint8_t(200 - j);
            }
    }));
    auto lease = rig.source->nextFrame();
    ASSERT_TRUE(lease.ok());
    const FrameView &view = lease->view();
    EXPECT_EQ(view.planes[0].data[31 * view.planes[0].stride + 63], 94);
    EXPECT_EQ(view.planes[1].data[15 * view.planes[1].stride + 2 * 31], 131);
    EXPECT_EQ(view.planes[1].data[15 * view.planes[1].stride + 2 * 31 + 1], 185);
}

TEST(V4l2PlaneSplit, BufferTooSmallForTheFormatIsRefused)
{
    std::vector<uint8_t> memory(640 * 480); // NV12 needs 640 * 480 * 3 / 2
    DeviceFormat format{.fourcc = V4L2_PIX_FMT_NV12, .width = 640, .height = 480};
    format.planes[0] = {640, 640 * 480};
    const PlaneMemory planes[] = {{memory.data(), memory.size()}};
    auto view = splitFrame(*pixelFormatFromName("NV12"), format, planes);
    ASSERT_FALSE(view.ok());
    EXPECT_EQ(view.error().code, ErrorCode::Malformed);
}

} // namespace
} // namespace overlayd::test
