// SPDX-License-Identifier: Apache-2.0
// The pixel-format table against the V4L2 UAPI: fourccs, byte orders, bits per pixel, strides of odd widths.
#include "media/pixel_format.h"

#include <set>
#include <string>

#include <gtest/gtest.h>
#include <linux/videodev2.h>

namespace overlayd {
namespace {

std::string fourccString(uint32_t fourcc)
{
    return {char(fourcc & 0xff), char((fourcc >> 8) & 0xff), char((fourcc >> 16) & 0xff), char(fourcc >> 24)};
}

TEST(PixelFormat, FourccsAreTheV4l2Ones)
{
    EXPECT_EQ(fourccString(pixelFormatFromName("YUYV")->fourcc), "YUYV");
    EXPECT_EQ(fourccString(pixelFormatFromName("YUV420")->fourcc), "YU12");
    EXPECT_EQ(fourccString(pixelFormatFromName("YVU420")->fourcc), "YV12");
    EXPECT_EQ(fourccString(pixelFormatFromName("XRGB32")->fourcc), "BX24");
    EXPECT_EQ(fourccString(pixelFormatFromName("XBGR32")->fourcc), "XR24");
    EXPECT_EQ(fourccString(pixelFormatFromName("RGBA32")->fourcc), "AB24");
    EXPECT_EQ(fourccString(pixelFormatFromName("BGRA32")->fourcc), "RA24");
    EXPECT_EQ(pixelFormatFromFourcc(V4L2_PIX_FMT_NV12)->name, "NV12");
    EXPECT_EQ(pixelFormatFromFourcc(V4L2_PIX_FMT_MJPEG), nullptr);
}

TEST(PixelFormat, EntriesAreUnique)
{
    std::set<uint32_t> fourccs;
    std::set<std::string_view> names;
    for (const PixelFormatInfo &info : pixelFormats()) {
        EXPECT_TRUE(fourccs.insert(info.fourcc).second) << info.name;
        EXPECT_TRUE(names.insert(info.name).second) << info.name;
    }
    EXPECT_EQ(pixelFormats().size(), 19u);
}

// Memory order from the V4L2 "Packed RGB formats" table: XBGR32 is B G R X, BGRA32 is A B G R, and so on.
TEST(PixelFormat, RgbByteOrders)
{
    struct Expect {
        const char *name;
        int r, g, b, a;
    };
    const Expect expected[] = {
        {"RGB24", 0, 1, 2, -1},  {"BGR24", 2, 1, 0, -1},  {"XRGB32", 1, 2, 3, -1}, {"XBGR32", 2, 1, 0, -1},
        {"RGBX32", 0, 1, 2, -1}, {"BGRX32", 3, 2, 1, -1}, {"ARGB32", 1, 2, 3, 0},  {"ABGR32", 2, 1, 0, 3},
        {"RGBA32", 0, 1, 2, 3},  {"BGRA32", 3, 2, 1, 0},
    };
    for (const Expect &e : expected) {
        const PixelFormatInfo *info = pixelFormatFromName(e.name);
        ASSERT_NE(info, nullptr) << e.name;
        EXPECT_EQ(info->rOffset, e.r) << e.name;
        EXPECT_EQ(info->gOffset, e.g) << e.name;
        EXPECT_EQ(info->bOffset, e.b) << e.name;
        EXPECT_EQ(info->aOffset, e.a < 0 ? kNoComponent : e.a) << e.name;
    }
}

TEST(PixelFormat, BitsPerPixelMatchPlanes)
{
    for (const PixelFormatInfo &info : pixelFormats()) {
        unsigned bits = 0;
        for (unsigned p = 0; p < info.numPlanes; ++p)
            bits += 8 * info.planes[p].bytesPerGroup / info.planes[p].verticalSubSampling;
        EXPECT_EQ(bits / info.pixelsPerGroup, info.bitsPerPixel) << info.name;
    }
}

TEST(PixelFormat, OddSizesRoundUpToWholeGroups)
{
    const PixelFormatInfo &yuyv = *pixelFormatFromName("YUYV");
    EXPECT_EQ(yuyv.minStride(0, 5), 12u);
    const PixelFormatInfo &i420 = *pixelFormatFromName("YUV420");
    EXPECT_EQ(i420.minStride(0, 5), 6u);
    EXPECT_EQ(i420.minStride(1, 5), 3u);
    EXPECT_EQ(i420.planeHeight(1, 7), 4u);
    const PixelFormatInfo &nv16 = *pixelFormatFromName("NV16");
    EXPECT_EQ(nv16.planeHeight(1, 7), 7u);
    EXPECT_EQ(pixelFormatFromName("BGR24")->minStride(0, 5), 15u);
}

} // namespace
} // namespace overlayd
