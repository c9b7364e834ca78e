// SPDX-License-Identifier: Apache-2.0
// The pixel-format table: one entry per supported V4L2 format drives strides, plane sizes and subsampling.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace overlayd {

// How a format stores colour; the overlay picks its layer converter from this, never from the fourcc.
enum class ColourEncoding : uint8_t { Yuv, Rgb };

// Where the samples of a format sit. The planes' arrangement is described by PlaneInfo; this says what the bytes
// of one group mean.
enum class PixelLayout : uint8_t {
    PackedYuv422, // one plane, 2 pixels per group: Y0 Y1 Cb Cr at yOffset/cbOffset/crOffset
    SemiPlanar,   // Y plane + one interleaved CbCr plane (offsets within a 2-byte chroma group)
    Planar,       // Y plane + Cb plane + Cr plane (cbPlane/crPlane say which is which)
    PackedRgb,    // one plane, 1 pixel per group, r/g/b/a offsets within the pixel
    Grey,         // one plane of luma only
};

struct PlaneInfo {
    uint8_t bytesPerGroup = 0;       // bytes of this plane covering pixelsPerGroup pixels of one row
    uint8_t verticalSubSampling = 1; // luma rows per row of this plane
};

inline constexpr uint8_t kNoComponent = 0xff;

struct PixelFormatInfo {
    std::string_view name;
    uint32_t fourcc = 0; // V4L2_PIX_FMT_*
    ColourEncoding encoding = ColourEncoding::Yuv;
    PixelLayout layout = PixelLayout::Grey;
    uint8_t bitsPerPixel = 0; // average over all planes, as V4L2 documents it
    uint8_t pixelsPerGroup = 1;
    uint8_t numPlanes = 1;
    std::array<PlaneInfo, 3> planes{};
    uint8_t hSubSampling = 1; // chroma: luma columns per chroma sample
    uint8_t vSubSampling = 1; // chroma: luma rows per chroma sample
    // Byte offsets inside one group of the plane holding the component (kNoComponent when absent).
    std::array<uint8_t, 2> yOffset{kNoComponent, kNoComponent}; // Y of the group's first and second pixel
    uint8_t cbOffset = kNoComponent, crOffset = kNoComponent;
    uint8_t cbPlane = 0, crPlane = 0;
    uint8_t rOffset = kNoComponent, gOffset = kNoComponent, bOffset = kNoComponent;
    uint8_t aOffset = kNoComponent; // a real alpha byte; an X (padding) byte is simply not named

    // Minimum bytesperline of a plane for a frame width: whole groups, a partial last group rounded up.
    unsigned minStride(unsigned plane, unsigned width) const;
    // Rows of a plane for a frame height (odd heights round up).
    unsigned planeHeight(unsigned plane, unsigned height) const;
};

// nullptr when the format is not in the table.
const PixelFormatInfo *pixelFormatFromFourcc(uint32_t fourcc);
const PixelFormatInfo *pixelFormatFromName(std::string_view name);

// Every entry, for tests and for listing what the daemon accepts.
std::span<const PixelFormatInfo> pixelFormats();

} // namespace overlayd
