// SPDX-License-Identifier: Apache-2.0
// Finding a device: by path, by /dev/v4l/by-id link, by card name; the errors when it is missing or wrong.
#include <gtest/gtest.h>

#include "drivers/v4l2/video_device.h"
#include "test_devices.h"

namespace overlayd::test {
namespace {

TEST(V4l2DeviceOpen, ByPathAndByLink)
{
    FakeSyscalls kernel;
    FakeDevice &device = kernel.add("/dev/video3", {"/dev/v4l/by-id/usb-Fake_Cam-video-index0"});
    device.formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}}, {30.0}}};
    auto byPath = VideoDevice::open(kernel, "/dev/video3", Direction::Capture);
    ASSERT_TRUE(byPath.ok()) << byPath.error().message;
    EXPECT_EQ((*byPath)->describe(), "/dev/video3 (Fake Cam)");
    auto byLink = VideoDevice::open(kernel, "/dev/v4l/by-id/usb-Fake_Cam-video-index0", Direction::Capture);
    ASSERT_TRUE(byLink.ok()) << byLink.error().message;
    EXPECT_EQ(kernel.openFds(), 2u);
}

TEST(V4l2DeviceOpen, ByCardNamePrefersAnExactMatchAndSkipsOtherDirections)
{
    FakeSyscalls kernel;
    kernel.add("/dev/video0").card = "vivid-extra";
    FakeDevice &output = kernel.add("/dev/video1");
    output.card = "vivid";
    output.bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT;
    kernel.add("/dev/video2").card = "vivid";
    auto device = VideoDevice::open(kernel, "vivid", Direction::Capture);
    ASSERT_TRUE(device.ok()) << device.error().message;
    EXPECT_EQ((*device)->describe(), "/dev/video2 (vivid)");
    EXPECT_EQ(kernel.openFds(), 1u); // the probed nodes were closed again

    auto out = VideoDevice::open(kernel, "vivid", Direction::Output);
    ASSERT_TRUE(out.ok()) << out.error().message;
    EXPECT_EQ((*out)->describe(), "/dev/video1 (vivid)");
    EXPECT_EQ((*out)->bufferType(), uint32_t(V4L2_BUF_TYPE_VIDEO_OUTPUT));

    auto prefix = VideoDevice::open(kernel, "vivid-ex", Direction::Capture);
    ASSERT_TRUE(prefix.ok());
    EXPECT_EQ((*prefix)->describe(), "/dev/video0 (vivid-extra)");
}

TEST(V4l2DeviceOpen, MissingDeviceIsNotFound)
{
    FakeSyscalls kernel;
    kernel.add("/dev/video0").card = "Integrated Camera";
    auto byPath = VideoDevice::open(kernel, "/dev/video7", Direction::Capture);
    ASSERT_FALSE(byPath.ok());
    EXPECT_EQ(byPath.error().code, ErrorCode::NotFound);
    EXPECT_NE(byPath.error().message.find("/dev/video7"), std::string::npos);

    auto byCard = VideoDevice::open(kernel, "vivid", Direction::Capture);
    ASSERT_FALSE(byCard.ok());
    EXPECT_EQ(byCard.error().code, ErrorCode::NotFound);
    EXPECT_EQ(byCard.error().message,
              "no video capture device with card name 'vivid' (found: /dev/video0 'Integrated Camera')");

    kernel.unplug("/dev/video0");
    auto unplugged = VideoDevice::open(kernel, "/dev/video0", Direction::Capture);
    ASSERT_FALSE(unplugged.ok());
    EXPECT_EQ(unplugged.error().code, ErrorCode::NotFound);
}

TEST(V4l2DeviceOpen, OutputOnlyNodeIsNotACaptureDevice)
{
    FakeSyscalls kernel;
    kernel.add("/dev/video1").bufferType = V4L2_BUF_TYPE_VIDEO_OUTPUT;
    auto device = VideoDevice::open(kernel, "/dev/video1", Direction::Capture);
    ASSERT_FALSE(device.ok());
    EXPECT_EQ(device.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(kernel.openFds(), 0u);
}

TEST(V4l2DeviceOpen, MultiPlanarDeviceUsesTheMplaneBufferType)
{
    FakeSyscalls kernel;
    kernel.add("/dev/video0").bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    auto device = VideoDevice::open(kernel, "/dev/video0", Direction::Capture);
    ASSERT_TRUE(device.ok());
    EXPECT_TRUE((*device)->multiPlanar());
}

} // namespace
} // namespace overlayd::test
