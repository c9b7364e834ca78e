// SPDX-License-Identifier: Apache-2.0
// Negotiation: Valid, Adjusted (logged once, with the exact line) and Invalid (listing the offers).
#include <gtest/gtest.h>

#include "drivers/v4l2/negotiation.h"
#include "test_devices.h"

namespace overlayd::test {
namespace {

TEST(V4l2Negotiation, ValidRequestIsUsedAsItIsAndNotLogged)
{
    CaptureRig rig;
    addYuyvCamera(rig.kernel);
    rig.make(captureOptions("YUYV", 1280, 720, 30.0));
    auto format = rig.source->start();
    ASSERT_TRUE(format.ok()) << format.error().message;
    EXPECT_EQ(format->format->name, "YUYV");
    EXPECT_EQ(format->width, 1280u);
    EXPECT_EQ(format->height, 720u);
    EXPECT_EQ(format->stride, 2560u); // the driver's bytesperline: 1280 pixels * 2 bytes
    EXPECT_DOUBLE_EQ(format->fps, 30.0);
    EXPECT_TRUE(rig.log.empty());
    EXPECT_TRUE(rig.source->adjustment().empty());
}

TEST(V4l2Negotiation, UnofferedSizeIsAdjustedAndLoggedOnceAcrossRestarts)
{
    CaptureRig rig;
    addYuyvCamera(rig.kernel);
    rig.make(captureOptions("YUYV", 1920, 1080, 30.0));
    for (int round = 0; round < 3; ++round) {
        auto format = rig.source->start();
        ASSERT_TRUE(format.ok()) << format.error().message;
        EXPECT_EQ(format->width, 1280u);
        EXPECT_EQ(format->height, 720u);
        rig.source->stop();
    }
    ASSERT_EQ(rig.log.size(), 1u);
    EXPECT_EQ(rig.log[0], "/dev/video0 (Fake Cam): asked 1920x1080@30 YUYV, got 1280x720@30 YUYV");
}

TEST(V4l2Negotiation, UnofferedRateIsAdjustedToTheNearest)
{
    CaptureRig rig;
    addYuyvCamera(rig.kernel);
    rig.make(captureOptions("YUYV", 640, 480, 25.0));
    auto format = rig.source->start();
    ASSERT_TRUE(format.ok()) << format.error().message;
    EXPECT_DOUBLE_EQ(format->fps, 30.0); // 5 from 25, where 15 is 10 away
    ASSERT_EQ(rig.log.size(), 1u);
    EXPECT_EQ(rig.log[0], "/dev/video0 (Fake Cam): asked 640x480@25 YUYV, got 640x480@30 YUYV");
}

TEST(V4l2Negotiation, UnofferedFormatIsInvalidAndTheErrorListsTheOffers)
{
    CaptureRig rig;
    FakeDevice &device = rig.kernel.add("/dev/video0");
    device.formats = {{V4L2_PIX_FMT_YUYV, {{640, 480}, {1280, 720}}, {30.0}},
                      {V4L2_PIX_FMT_RGB24, {{320, 240}}, {30.0}}};
    rig.make(captureOptions("NV12", 640, 480, 30.0));
    auto format = rig.source->start();
    ASSERT_FALSE(format.ok());
    EXPECT_EQ(format.error().code, ErrorCode::ConfigError);
    EXPECT_EQ(format.error().message,
              "/dev/video0 (Fake Cam) does not offer NV12; it offers YUYV 640x480 1280x720, RGB3 320x240");
    EXPECT_EQ(rig.kernel.openFds(), 0u); // a failed start leaves nothing open
}

TEST(V4l2Negotiation, UnknownFormatNameIsAConfigError)
{
    CaptureRig rig;
    addYuyvCamera(rig.kernel);
    rig.make(captureOptions("YUY2", 640, 480, 30.0));
    auto format = rig.source->start();
    ASSERT_FALSE(format.ok());
    EXPECT_EQ(format.error().code, ErrorCode::ConfigError);
}

TEST(V4l2Negotiation, MultiPlaneVariantIsAcceptedForItsFormat)
{
    const OfferedFormat offers[] = {{V4L2_PIX_FMT_NV12M, {{640, 640, 1, 480, 480, 1}}}};
    const FormatChoice choice = chooseFormat({pixelFormatFromName("NV12"), 640, 480, 30.0}, offers);
    EXPECT_EQ(choice.verdict, Verdict::Valid);
    EXPECT_EQ(choice.fourcc, uint32_t(V4L2_PIX_FMT_NV12M));
}

TEST(V4l2Negotiation, StepwiseSizesClampAndAlignToTheStep)
{
    const OfferedFormat offers[] = {{V4L2_PIX_FMT_YUYV, {{16, 1920, 16, 16, 1080, 8}}}};
    FormatChoice choice = chooseFormat({pixelFormatFromName("YUYV"), 1000, 500, 30.0}, offers);
    EXPECT_EQ(choice.verdict, Verdict::Adjusted);
    EXPECT_EQ(choice.width, 992u); // 16 + 61 * 16
    EXPECT_EQ(choice.height, 496u);
    choice = chooseFormat({pixelFormatFromName("YUYV"), 4000, 8, 30.0}, offers);
    EXPECT_EQ(choice.width, 1920u);
    EXPECT_EQ(choice.height, 16u);
    choice = chooseFormat({pixelFormatFromName("YUYV"), 640, 480, 30.0}, offers);
    EXPECT_EQ(choice.verdict, Verdict::Valid);
}

TEST(V4l2Negotiation, RatesWithinAHundredthAreTheSame)
{
    const RateRange ntsc[] = {{30000.0 / 1001, 30000.0 / 1001}, {15.0, 15.0}};
    EXPECT_DOUBLE_EQ(chooseRate(29.97, ntsc), 29.97);
    EXPECT_DOUBLE_EQ(chooseRate(30.0, ntsc), 30000.0 / 1001);
    EXPECT_DOUBLE_EQ(chooseRate(10.0, ntsc), 15.0);
    const RateRange continuous[] = {{1.0, 60.0}};
    EXPECT_DOUBLE_EQ(chooseRate(24.0, continuous), 24.0);
    EXPECT_DOUBLE_EQ(chooseRate(120.0, continuous), 60.0);
    EXPECT_DOUBLE_EQ(chooseRate(25.0, {}), 25.0); // the driver does not enumerate: S_PARM decides
}

TEST(V4l2Negotiation, MjpegIsPickedOnlyWhenTheFormatIsNotOffered)
{
    const OfferedFormat offers[] = {{V4L2_PIX_FMT_YUYV, {{640, 640, 1, 480, 480, 1}}},
                                    {V4L2_PIX_FMT_MJPEG, {{1280, 1280, 1, 720, 720, 1}}}};
    // YUYV is offered, if only at another size: it wins over MJPEG at the asked size.
    FormatChoice choice = chooseFormat({pixelFormatFromName("YUYV"), 1280, 720, 30.0}, offers);
    EXPECT_EQ(choice.fourcc, uint32_t(V4L2_PIX_FMT_YUYV));
    EXPECT_EQ(choice.verdict, Verdict::Adjusted);
    choice = chooseFormat({pixelFormatFromName("NV12"), 1280, 720, 30.0}, offers);
    EXPECT_EQ(choice.fourcc, uint32_t(V4L2_PIX_FMT_MJPEG));
    EXPECT_EQ(choice.width, 1280u);
}

} // namespace
} // namespace overlayd::test
