// SPDX-License-Identifier: Apache-2.0
// Pixel formats: V4L2 names memory bytes in order, DRM (libcamera) names a little-endian word from its top bit, so
// the packed RGB names are mirrored: V4L2 RGB24 (bytes R G B) is DRM BGR888 ([23:0] B:G:R little endian).
#include "drivers/libcamera/libcamera_formats.h"

#include <array>
#include <string_view>
#include <utility>

#include <libcamera/formats.h>

namespace overlayd {

namespace {

namespace f = libcamera::formats;

const std::array<std::pair<std::string_view, libcamera::PixelFormat>, 19> kFormats{{
    {"GREY", f::R8},         {"YUYV", f::YUYV},    {"UYVY", f::UYVY}, {"YVYU", f::YVYU},
    {"NV12", f::NV12},       {"NV21", f::NV21},    {"NV16", f::NV16}, {"YUV420", f::YUV420},
    {"YVU420", f::YVU420},   {"RGB24", f::BGR888}, // bytes R G B
    {"BGR24", f::RGB888},                          // bytes B G R
    {"XRGB32", f::BGRX8888},                       // bytes X R G B
    {"XBGR32", f::XRGB8888},                       // bytes B G R X
    {"RGBX32", f::XBGR8888},                       // bytes R G B X
    {"BGRX32", f::RGBX8888},                       // bytes X B G R
    {"ARGB32", f::BGRA8888},                       // bytes A R G B
    {"ABGR32", f::ARGB8888},                       // bytes B G R A
    {"RGBA32", f::ABGR8888},                       // bytes R G B A
    {"BGRA32", f::RGBA8888},                       // bytes A B G R
}};

} // namespace

// Every entry of the project's table has one here (tests/unit/libcamera checks it).
std::optional<libcamera::PixelFormat> toLibcamera(const PixelFormatInfo &format)
{
    for (const auto &[name, drm] : kFormats) {
        if (name == format.name)
            return drm;
    }
    return std::nullopt;
}

const PixelFormatInfo *fromLibcamera(const libcamera::PixelFormat &format)
{
    for (const auto &[name, drm] : kFormats) {
        if (drm == format)
            return pixelFormatFromName(name);
    }
    return nullptr;
}

std::string formatName(const libcamera::PixelFormat &format)
{
    if (const PixelFormatInfo *info = fromLibcamera(format))
        return std::string(info->name);
    return format.toString();
}

} // namespace overlayd
