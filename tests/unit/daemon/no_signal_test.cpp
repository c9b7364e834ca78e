// SPDX-License-Identifier: Apache-2.0
// NO SIGNAL frames: every byte replaced (dark grey) with light text in the middle, in each kind of pixel format;
// checked after converting to BGR with OpenCV, not with our own converters.
#include "daemon/no_signal.h"

#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

cv::Mat toBgr(const FrameView &frame)
{
    const std::string_view name = frame.format->name;
    cv::Mat bgr;
    if (name == "YUYV") {
        cv::Mat packed(int(frame.height), int(frame.width), CV_8UC2, frame.planes[0].data, frame.planes[0].stride);
        cv::cvtColor(packed, bgr, cv::COLOR_YUV2BGR_YUYV);
    } else if (name == "NV12") {
        // NV12 in one buffer: the CbCr plane follows the Y plane directly when rows are packed.
        cv::Mat planes(int(frame.height * 3 / 2), int(frame.width), CV_8UC1, frame.planes[0].data);
        cv::cvtColor(planes, bgr, cv::COLOR_YUV2BGR_NV12);
    } else if (name == "RGB24") {
        cv::Mat rgb(int(frame.height), int(frame.width), CV_8UC3, frame.planes[0].data, frame.planes[0].stride);
        cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    }
    return bgr;
}

class NoSignalTest : public ::testing::TestWithParam<const char *>
{};

TEST_P(NoSignalTest, DarkFrameWithLightTextInTheMiddle)
{
    StreamFormat format;
    format.format = pixelFormatFromName(GetParam());
    ASSERT_NE(format.format, nullptr);
    format.width = 320;
    format.height = 240;
    auto frame = NoSignalFrame::create(format, "/dev/video0: No such device");
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    FrameView view = frame->view();
    if (std::string_view(GetParam()) == "NV12") { // toBgr relies on packed rows
        ASSERT_EQ(view.planes[1].data, view.planes[0].data + size_t(format.width) * format.height);
    }
    const cv::Mat bgr = toBgr(view);
    ASSERT_FALSE(bgr.empty());
    cv::Mat grey;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    // OpenCV converts YUV as BT.601 limited range, our default colorimetry: the background comes back near 48.
    const cv::Rect corner(0, 0, 40, 40), middle(20, 60, 280, 120);
    double low = 0, high = 0;
    cv::minMaxLoc(grey(corner), &low, &high);
    EXPECT_NEAR(low, 48, 3);
    EXPECT_NEAR(high, 48, 3);
    cv::minMaxLoc(grey(middle), &low, &high);
    EXPECT_GT(high, 200); // the text
    EXPECT_GT(cv::countNonZero(grey(middle) > 150), 200);
}

INSTANTIATE_TEST_SUITE_P(Formats, NoSignalTest, ::testing::Values("YUYV", "NV12", "RGB24"));

} // namespace
} // namespace overlayd
