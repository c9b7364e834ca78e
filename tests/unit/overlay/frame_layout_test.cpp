// SPDX-License-Identifier: Apache-2.0
// Frame layouts (tight, padded, odd) and the frame check that guards every blend; V4L2 colorimetry defaults.
#include "media/frame.h"

#include <gtest/gtest.h>
#include <linux/videodev2.h>

#include "media/colorimetry.h"

namespace overlayd {
namespace {

TEST(FrameLayout, Nv12Tight)
{
    auto layout = makeFrameLayout(*pixelFormatFromName("NV12"), 640, 480);
    ASSERT_TRUE(layout);
    EXPECT_EQ(layout->planes[0].stride, 640u);
    EXPECT_EQ(layout->planes[1].offset, 640u * 480);
    EXPECT_EQ(layout->planes[1].stride, 640u);
    EXPECT_EQ(layout->totalSize, 640u * 480 * 3 / 2);
}

TEST(FrameLayout, I420PaddedHalvesChromaStride)
{
    auto layout = makeFrameLayout(*pixelFormatFromName("YUV420"), 636, 478, 704);
    ASSERT_TRUE(layout);
    EXPECT_EQ(layout->planes[1].stride, 352u);
    EXPECT_EQ(layout->planes[2].offset, 704u * 478 + 352u * 239);
    EXPECT_EQ(layout->totalSize, 704u * 478 + 2 * 352u * 239);
}

TEST(FrameLayout, OddYuyv)
{
    auto layout = makeFrameLayout(*pixelFormatFromName("YUYV"), 5, 3);
    ASSERT_TRUE(layout);
    EXPECT_EQ(layout->planes[0].stride, 12u);
    EXPECT_EQ(layout->totalSize, 36u);
}

TEST(FrameLayout, RefusesShortStrideAndEmptySize)
{
    auto shortStride = makeFrameLayout(*pixelFormatFromName("RGB24"), 10, 10, 29);
    ASSERT_FALSE(shortStride);
    EXPECT_EQ(shortStride.error().message, "RGB24 stride 29 is below 30 for width 10");
    EXPECT_FALSE(makeFrameLayout(*pixelFormatFromName("GREY"), 0, 10));
}

TEST(FrameLayout, CheckFrameRefusesSmallPlanes)
{
    auto layout = makeFrameLayout(*pixelFormatFromName("NV12"), 8, 4);
    ASSERT_TRUE(layout);
    std::vector<uint8_t> bytes(layout->totalSize);
    FrameView frame = layout->view(bytes.data());
    EXPECT_TRUE(checkFrame(frame));
    frame.planes[1].size -= 1;
    EXPECT_FALSE(checkFrame(frame));
    frame = layout->view(bytes.data());
    frame.planes[0].stride = 7;
    EXPECT_FALSE(checkFrame(frame));
}

TEST(Colorimetry, V4l2Defaults)
{
    const Colorimetry sd = colorimetryFromV4l2(V4L2_COLORSPACE_SMPTE170M, V4L2_YCBCR_ENC_DEFAULT, 0);
    EXPECT_EQ(sd, (Colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited}));
    const Colorimetry hd = colorimetryFromV4l2(V4L2_COLORSPACE_REC709, V4L2_YCBCR_ENC_DEFAULT, 0);
    EXPECT_EQ(hd, (Colorimetry{YcbcrMatrix::Bt709, ColourRange::Limited}));
    const Colorimetry jpeg = colorimetryFromV4l2(V4L2_COLORSPACE_JPEG, V4L2_YCBCR_ENC_DEFAULT, 0);
    EXPECT_EQ(jpeg, (Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full}));
}

} // namespace
} // namespace overlayd
