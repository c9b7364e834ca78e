// SPDX-License-Identifier: Apache-2.0
// Helpers of the JPEG encoder tests: frames of a colourful pattern, JPEG headers, and the error of a decoded JPEG
// against our own conversion of the frame.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "media/colorimetry.h"
#include "media/frame_buffer.h"

namespace overlayd::test {

// `formatName` frame of the pattern encoded in `colorimetry`; plane 0's stride padded by stridePadding bytes.
FrameBuffer patternFrame(const std::string &formatName, unsigned width, unsigned height, Colorimetry colorimetry,
                         unsigned stridePadding = 0);

struct JpegHeader {
    int width = 0, height = 0, subsampling = -1; // TJSAMP_*
};
JpegHeader readHeader(const std::vector<uint8_t> &jpeg);

// Mean absolute difference per channel (R, G, B) between the JPEG as OpenCV decodes it (JFIF: full-range BT.601)
// and frameToRgb(frame, colorimetry); every channel 255 when the JPEG does not decode or the sizes differ.
std::array<double, 3> meanError(const std::vector<uint8_t> &jpeg, const FrameView &frame, Colorimetry colorimetry);
// The largest difference of any channel at the centres of the bars, away from every edge: where colour is flat,
// so that only the colour conversion and JPEG's quantisation of a flat block remain.
int worstBarError(const std::vector<uint8_t> &jpeg, const FrameView &frame, Colorimetry colorimetry);
double worstChannel(const std::array<double, 3> &error);

} // namespace overlayd::test
