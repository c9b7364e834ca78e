// SPDX-License-Identifier: Apache-2.0
// Colorimetry of a YCbCr frame: the colour matrix and the quantization range, always named, never guessed.
#pragma once

#include <cstdint>

namespace overlayd {

enum class YcbcrMatrix : uint8_t { Bt601, Bt709 };
enum class ColourRange : uint8_t { Limited, Full };

// The default, BT.601 limited range, is what V4L2 assumes for SDTV YUV and what most USB cameras send.
struct Colorimetry {
    YcbcrMatrix matrix = YcbcrMatrix::Bt601;
    ColourRange range = ColourRange::Limited;

    bool operator==(const Colorimetry &) const = default;
};

// From v4l2_pix_format's colorspace, ycbcr_enc and quantization, resolving their DEFAULT values as the kernel's
// V4L2_MAP_*_DEFAULT macros do. Encodings we do not model (BT.2020, SMPTE 240M) map to BT.709, the nearest.
Colorimetry colorimetryFromV4l2(uint32_t colorspace, uint32_t ycbcrEnc, uint32_t quantization);

const char *matrixName(YcbcrMatrix matrix);
const char *rangeName(ColourRange range);

} // namespace overlayd
