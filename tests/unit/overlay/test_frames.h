// SPDX-License-Identifier: Apache-2.0
// Test frames: owned buffers with padding and guard bytes, mid-grey fills, and conversion to BGR through OpenCV.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/pixel_format.h"

namespace overlayd::test {

inline constexpr size_t kGuardBytes = 64;
inline constexpr uint8_t kGuardValue = 0xa5;

// A frame in one buffer (planes back to back, as a single-planar V4L2 buffer) with guard bytes after it.
struct TestFrame {
    FrameLayout layout;
    std::vector<uint8_t> bytes;

    FrameView view() { return layout.view(bytes.data()); }
    uint8_t *plane(unsigned p) { return bytes.data() + layout.planes[p].offset; }
    const uint8_t *plane(unsigned p) const { return bytes.data() + layout.planes[p].offset; }
    unsigned stride(unsigned p) const { return layout.planes[p].stride; }
    bool guardIntact() const;
};

const PixelFormatInfo &format(const std::string &name);
// stridePadding bytes are added to the minimum stride of plane 0 (V4L2 derives the other planes' strides).
TestFrame makeFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding);

// Fills every visible sample with the encoding of one RGB colour (exact formulas, rounded); padding gets 0x5a so
// that a write into it shows.
void fillRgb(TestFrame &frame, Colorimetry colorimetry, uint8_t r, uint8_t g, uint8_t b);

// The frame as 8-bit BGR, WxH. YUV formats go through OpenCV's BT.601 limited-range converters (cvtColor
// YUV2BGR_*), reading the frame's own memory where OpenCV has the format and the size is even; otherwise the samples
// are first repacked into an even-sized I420 or YUYV image with the last column/row repeated.
cv::Mat toBgr(const TestFrame &frame);

// The pixels (x, y) whose colour a byte of a plane carries; empty for padding.
std::vector<cv::Point> pixelsOfByte(const TestFrame &frame, unsigned plane, unsigned row, unsigned column);

// What a byte holds: 'Y', 'U' (Cb), 'V' (Cr), 'R', 'G', 'B', 'A', 'X', or 0 for padding.
char byteKind(const TestFrame &frame, unsigned plane, unsigned column);

} // namespace overlayd::test
