// SPDX-License-Identifier: Apache-2.0
// Every format of the project's table against libcamera's: found both ways, and the same bytes in memory as
// libcamera's own name for it says (DRM names a little-endian word from its top component down).
#include <cctype>
#include <string>

#include <gtest/gtest.h>

#include "drivers/libcamera/libcamera_formats.h"

namespace overlayd {
namespace {

// "XRGB8888" -> "XRGB": the components from the word's top bits down.
std::string componentsOf(const std::string &drmName)
{
    std::string letters;
    for (const char c : drmName) {
        if (std::isdigit(static_cast<unsigned char>(c)))
            break;
        letters += c;
    }
    return letters;
}

TEST(Formats, EveryTableFormatMapsBothWays)
{
    for (const PixelFormatInfo &info : pixelFormats()) {
        SCOPED_TRACE(std::string(info.name));
        const auto drm = toLibcamera(info);
        ASSERT_TRUE(drm.has_value());
        EXPECT_EQ(fromLibcamera(*drm), &info);
        EXPECT_EQ(formatName(*drm), info.name);
    }
}

TEST(Formats, PackedRgbBytesAreWhatLibcamerasNameSays)
{
    int checked = 0;
    for (const PixelFormatInfo &info : pixelFormats()) {
        if (info.encoding != ColourEncoding::Rgb)
            continue;
        SCOPED_TRACE(std::string(info.name));
        const std::string components = componentsOf(toLibcamera(info)->toString());
        const unsigned bytes = unsigned(components.size());
        ASSERT_EQ(bytes * 8, info.bitsPerPixel);
        // Little endian: the last component named sits in byte 0.
        const auto byteOf = [&](char component) {
            return bytes - 1 - unsigned(components.find(component));
        };
        EXPECT_EQ(info.rOffset, byteOf('R'));
        EXPECT_EQ(info.gOffset, byteOf('G'));
        EXPECT_EQ(info.bOffset, byteOf('B'));
        if (components.find('A') != std::string::npos) {
            EXPECT_EQ(info.aOffset, byteOf('A'));
        }
        ++checked;
    }
    EXPECT_GE(checked, 10);
}

TEST(Formats, YuvAndGreyKeepTheirNames)
{
    for (const PixelFormatInfo &info : pixelFormats()) {
        if (info.encoding == ColourEncoding::Rgb)
            continue;
        const std::string drm = toLibcamera(info)->toString();
        EXPECT_EQ(drm, info.name == "GREY" ? "R8" : std::string(info.name)) << info.name;
    }
}

TEST(Formats, FormatsOverlaydCannotUseHaveNoEntry)
{
    EXPECT_EQ(fromLibcamera(libcamera::PixelFormat::fromString("SRGGB10_CSI2P")), nullptr);
    EXPECT_EQ(fromLibcamera(libcamera::PixelFormat::fromString("MJPEG")), nullptr);
    EXPECT_EQ(formatName(libcamera::PixelFormat::fromString("SBGGR8")), "SBGGR8");
}

} // namespace
} // namespace overlayd
