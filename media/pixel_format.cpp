// SPDX-License-Identifier: Apache-2.0
// The pixel-format table. Byte orders follow the V4L2 UAPI (the comments in linux/videodev2.h give memory order).
#include "media/pixel_format.h"

#include <linux/videodev2.h>

namespace overlayd {

namespace {

constexpr PixelFormatInfo packed422(std::string_view name, uint32_t fourcc, uint8_t y0, uint8_t y1, uint8_t cb,
                                    uint8_t cr)
{
    return {.name = name,
            .fourcc = fourcc,
            .encoding = ColourEncoding::Yuv,
            .layout = PixelLayout::PackedYuv422,
            .bitsPerPixel = 16,
            .pixelsPerGroup = 2,
            .numPlanes = 1,
            .planes = {{{4, 1}}},
            .hSubSampling = 2,
            .vSubSampling = 1,
            .yOffset = {y0, y1},
            .cbOffset = cb,
            .crOffset = cr};
}

// Y plane plus one CbCr plane; vSub 2 is 4:2:0, 1 is 4:2:2.
constexpr PixelFormatInfo semiPlanar(std::string_view name, uint32_t fourcc, uint8_t vSub, uint8_t cb, uint8_t cr)
{
    return {.name = name,
            .fourcc = fourcc,
            .encoding = ColourEncoding::Yuv,
            .layout = PixelLayout::SemiPlanar,
            .bitsPerPixel = static_cast<uint8_t>(vSub == 2 ? 12 : 16),
            .pixelsPerGroup = 2,
            .numPlanes = 2,
            .planes = {{{2, 1}, {2, vSub}}},
            .hSubSampling = 2,
            .vSubSampling = vSub,
            .yOffset = {0, 1},
            .cbOffset = cb,
            .crOffset = cr,
            .cbPlane = 1,
            .crPlane = 1};
}

constexpr PixelFormatInfo planar420(std::string_view name, uint32_t fourcc, uint8_t cbPlane, uint8_t crPlane)
{
    return {.name = name,
            .fourcc = fourcc,
            .encoding = ColourEncoding::Yuv,
            .layout = PixelLayout::Planar,
            .bitsPerPixel = 12,
            .pixelsPerGroup = 2,
            .numPlanes = 3,
            .planes = {{{2, 1}, {1, 2}, {1, 2}}},
            .hSubSampling = 2,
            .vSubSampling = 2,
            .yOffset = {0, 1},
            .cbOffset = 0,
            .crOffset = 0,
            .cbPlane = cbPlane,
            .crPlane = crPlane};
}

constexpr PixelFormatInfo packedRgb(std::string_view name, uint32_t fourcc, uint8_t bytes, uint8_t r, uint8_t g,
                                    uint8_t b, uint8_t a = kNoComponent)
{
    return {.name = name,
            .fourcc = fourcc,
            .encoding = ColourEncoding::Rgb,
            .layout = PixelLayout::PackedRgb,
            .bitsPerPixel = static_cast<uint8_t>(bytes * 8),
            .pixelsPerGroup = 1,
            .numPlanes = 1,
            .planes = {{{bytes, 1}}},
            .rOffset = r,
            .gOffset = g,
            .bOffset = b,
            .aOffset = a};
}

constexpr PixelFormatInfo grey()
{
    return {.name = "GREY",
            .fourcc = V4L2_PIX_FMT_GREY,
            .encoding = ColourEncoding::Yuv,
            .layout = PixelLayout::Grey,
            .bitsPerPixel = 8,
            .pixelsPerGroup = 1,
            .numPlanes = 1,
            .planes = {{{1, 1}}},
            .yOffset = {0, kNoComponent}};
}

// Memory byte order of each RGB entry is spelled out because the V4L2 names do not say it consistently.
constexpr PixelFormatInfo kFormats[] = {
    packed422("YUYV", V4L2_PIX_FMT_YUYV, 0, 2, 1, 3), // Y0 Cb Y1 Cr
    packed422("UYVY", V4L2_PIX_FMT_UYVY, 1, 3, 0, 2), // Cb Y0 Cr Y1
    packed422("YVYU", V4L2_PIX_FMT_YVYU, 0, 2, 3, 1), // Y0 Cr Y1 Cb
    semiPlanar("NV12", V4L2_PIX_FMT_NV12, 2, 0, 1),
    semiPlanar("NV21", V4L2_PIX_FMT_NV21, 2, 1, 0),
    semiPlanar("NV16", V4L2_PIX_FMT_NV16, 1, 0, 1),
    planar420("YUV420", V4L2_PIX_FMT_YUV420, 1, 2),          // YU12 / I420: Y, Cb, Cr
    planar420("YVU420", V4L2_PIX_FMT_YVU420, 2, 1),          // YV12: Y, Cr, Cb
    packedRgb("RGB24", V4L2_PIX_FMT_RGB24, 3, 0, 1, 2),      // R G B
    packedRgb("BGR24", V4L2_PIX_FMT_BGR24, 3, 2, 1, 0),      // B G R
    packedRgb("XRGB32", V4L2_PIX_FMT_XRGB32, 4, 1, 2, 3),    // X R G B
    packedRgb("XBGR32", V4L2_PIX_FMT_XBGR32, 4, 2, 1, 0),    // B G R X
    packedRgb("RGBX32", V4L2_PIX_FMT_RGBX32, 4, 0, 1, 2),    // R G B X
    packedRgb("BGRX32", V4L2_PIX_FMT_BGRX32, 4, 3, 2, 1),    // X B G R
    packedRgb("ARGB32", V4L2_PIX_FMT_ARGB32, 4, 1, 2, 3, 0), // A R G B
    packedRgb("ABGR32", V4L2_PIX_FMT_ABGR32, 4, 2, 1, 0, 3), // B G R A
    packedRgb("RGBA32", V4L2_PIX_FMT_RGBA32, 4, 0, 1, 2, 3), // R G B A
    packedRgb("BGRA32", V4L2_PIX_FMT_BGRA32, 4, 3, 2, 1, 0), // A B G R
    grey(),
};

} // namespace

unsigned PixelFormatInfo::minStride(unsigned plane, unsigned width) const
{
    const unsigned groups = (width + pixelsPerGroup - 1) / pixelsPerGroup;
    return groups * planes[plane].bytesPerGroup;
}

unsigned PixelFormatInfo::planeHeight(unsigned plane, unsigned height) const
{
    const unsigned sub = planes[plane].verticalSubSampling;
    return (height + sub - 1) / sub;
}

const PixelFormatInfo *pixelFormatFromFourcc(uint32_t fourcc)
{
    for (const PixelFormatInfo &info : kFormats) {
        if (info.fourcc == fourcc)
            return &info;
    }
    return nullptr;
}

const PixelFormatInfo *pixelFormatFromName(std::string_view name)
{
    for (const PixelFormatInfo &info : kFormats) {
        if (info.name == name)
            return &info;
    }
    return nullptr;
}

std::span<const PixelFormatInfo> pixelFormats()
{
    return kFormats;
}

} // namespace overlayd
