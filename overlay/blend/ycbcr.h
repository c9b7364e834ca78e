// SPDX-License-Identifier: Apache-2.0
// Premultiplied RGB -> premultiplied Y'CbCr code values for a named colorimetry.
#pragma once

#include <cstdint>

#include "media/colorimetry.h"

namespace overlayd {

// Sums of premultiplied 8-bit samples over n pixels; their mean is the coverage-weighted colour of a group.
struct PremultipliedSum {
    float r = 0, g = 0, b = 0, a = 0;
    unsigned count = 0;

    void add(const uint8_t *rgba)
    {
        r += rgba[0], g += rgba[1], b += rgba[2], a += rgba[3];
        ++count;
    }
};

// A sample ready for the blend: out = value + in * (255 - alpha) / 255, with value <= alpha.
struct BlendSample {
    uint8_t value = 0;
    uint8_t alpha = 0;
};

struct YcbcrBlendSamples {
    BlendSample y, cb, cr;
};

class YcbcrEncoder
{
public:
    explicit YcbcrEncoder(Colorimetry colorimetry);

    // Luma of one premultiplied RGBA pixel.
    BlendSample luma(const uint8_t *rgba) const;
    // Y, Cb and Cr of the mean of the summed pixels: chroma of a macropixel blends with its coverage-weighted colour.
    YcbcrBlendSamples encode(const PremultipliedSum &sum) const;

private:
    float kr_, kb_;
    float yOffset_, yScale_, cScale_;
};

} // namespace overlayd
