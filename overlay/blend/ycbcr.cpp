// SPDX-License-Identifier: Apache-2.0
// The BT.601/BT.709 encoding equations (ITU-R BT.601-7 and BT.709-6), applied to premultiplied colour.
#include "overlay/blend/ycbcr.h"

#include <algorithm>
#include <cmath>

namespace overlayd {

namespace {

// The encoding is affine in colour, so premultiplying moves the offset into alpha: a*(off + s*c) = a*off + s*(a*c).
// lrintf (one instruction) instead of std::round (a library call): it rounds halves to even, which moves a value
// by at most one code only when it lies exactly halfway.
inline BlendSample sample(float alpha, float offset, float scaledPremultiplied)
{
    const long a = std::lrintf(alpha);
    const long value = std::lrintf(alpha * (1.0f / 255.0f) * offset + scaledPremultiplied);
    // value <= alpha keeps the blend inside 0..255 without a per-pixel clamp.
    return {uint8_t(std::clamp(value, 0L, a)), uint8_t(a)};
}

} // namespace

YcbcrEncoder::YcbcrEncoder(Colorimetry colorimetry)
{
    const bool bt601 = colorimetry.matrix == YcbcrMatrix::Bt601;
    kr_ = bt601 ? 0.299f : 0.2126f;
    kb_ = bt601 ? 0.114f : 0.0722f;
    const bool limited = colorimetry.range == ColourRange::Limited;
    yOffset_ = limited ? 16.0f : 0.0f;
    yScale_ = limited ? 219.0f / 255.0f : 1.0f;
    cScale_ = limited ? 224.0f / 255.0f : 1.0f;
}

BlendSample YcbcrEncoder::luma(const uint8_t *rgba) const
{
    const float y = kr_ * rgba[0] + (1.0f - kr_ - kb_) * rgba[1] + kb_ * rgba[2];
    return sample(rgba[3], yOffset_, yScale_ * y);
}

YcbcrBlendSamples YcbcrEncoder::encode(const PremultipliedSum &sum) const
{
    const float n = float(std::max(sum.count, 1u));
    const float r = sum.r / n, g = sum.g / n, b = sum.b / n, a = sum.a / n;
    const float y = kr_ * r + (1.0f - kr_ - kb_) * g + kb_ * b;
    const float cb = (b - y) / (2.0f * (1.0f - kb_));
    const float cr = (r - y) / (2.0f * (1.0f - kr_));
    return {sample(a, yOffset_, yScale_ * y), sample(a, 128.0f, cScale_ * cb), sample(a, 128.0f, cScale_ * cr)};
}

} // namespace overlayd
