// SPDX-License-Identifier: Apache-2.0
// The BT.601/BT.709 equations (ITU-R BT.601-7, BT.709-6) between 8-bit R'G'B' and Y'CbCr code values.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "media/colorimetry.h"

namespace overlayd {

// Y' = kr R' + (1 - kr - kb) G' + kb B'; Cb = (B' - Y') / (2 (1 - kb)); Cr = (R' - Y') / (2 (1 - kr)), all on a
// 0..255 scale, then limited range maps Y' to 16..235 and Cb/Cr to 16..240 around 128.
struct YcbcrCoefficients {
    float kr = 0.299f, kb = 0.114f;
    float yOffset = 16.0f, yScale = 219.0f / 255.0f, cScale = 224.0f / 255.0f;

    static YcbcrCoefficients of(Colorimetry colorimetry)
    {
        const bool bt601 = colorimetry.matrix == YcbcrMatrix::Bt601;
        const bool limited = colorimetry.range == ColourRange::Limited;
        return {bt601 ? 0.299f : 0.2126f, bt601 ? 0.114f : 0.0722f, limited ? 16.0f : 0.0f,
                limited ? 219.0f / 255.0f : 1.0f, limited ? 224.0f / 255.0f : 1.0f};
    }

    float luma(float r, float g, float b) const { return kr * r + (1.0f - kr - kb) * g + kb * b; }
    // Code values before rounding, from R'G'B' and its luma.
    float yCode(float y) const { return yOffset + yScale * y; }
    float cbCode(float b, float y) const { return 128.0f + cScale * (b - y) / (2.0f * (1.0f - kb)); }
    float crCode(float r, float y) const { return 128.0f + cScale * (r - y) / (2.0f * (1.0f - kr)); }
};

// Rounds half up (the values are clamped to be non-negative first); cheaper than lround on the per-pixel path.
inline uint8_t toCode(float value)
{
    return uint8_t(int(std::clamp(value, 0.0f, 255.0f) + 0.5f));
}

} // namespace overlayd
