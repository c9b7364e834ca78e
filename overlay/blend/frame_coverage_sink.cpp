// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink: set-up per frame and per item, and the staging of a row() call's opacities for the kernels. Luma
// (or RGB) bytes and 4:2:2 chroma blend as rows arrive; 4:2:0 chroma opacity is summed over both luma rows of a
// macropixel and each sample blended once, as its second row arrives.
#include "overlay/blend/frame_coverage_sink.h"

#include "overlay/blend/div255.h"

#include <algorithm>
#include <cassert>

namespace overlayd {

FrameCoverageSink::FrameCoverageSink(const PixelFormatInfo &format, Colorimetry colorimetry)
    : format_(&format), colorimetry_(colorimetry), encoder_(colorimetry), layout_(layoutOf(format))
{}

FrameCoverageSink::Layout FrameCoverageSink::layoutOf(const PixelFormatInfo &format)
{
    Layout layout;
    layout.rgb = format.encoding == ColourEncoding::Rgb;
    layout.pixelBytes = format.planes[0].bytesPerGroup / format.pixelsPerGroup;
    layout.lumaStep = layout.pixelBytes;
    layout.lumaOffset = format.yOffset[0];
    layout.byteLuma = !layout.rgb && layout.lumaStep == 1;
    // Luma bytes sit at a fixed step in every YUV entry of the table (Y0 and Y1 of a group one pixel step apart).
    assert(layout.rgb || format.pixelsPerGroup == 1 || format.yOffset[1] == format.yOffset[0] + layout.lumaStep);
    layout.chroma = !layout.rgb && format.cbOffset != kNoComponent;
    if (layout.chroma) {
        assert(format.hSubSampling == 2 && format.vSubSampling <= 2);
        layout.chromaStep = format.planes[format.cbPlane].bytesPerGroup;
        layout.cbPlane = format.cbPlane, layout.crPlane = format.crPlane;
        layout.cbOffset = format.cbOffset, layout.crOffset = format.crOffset;
        layout.vSub = format.vSubSampling;
        layout.packed422 = layout.vSub == 1 && layout.cbPlane == 0;
        const bool sideBySide = layout.cbOffset + 1 == layout.crOffset || layout.crOffset + 1 == layout.cbOffset;
        if (layout.chromaStep == 2 && layout.cbPlane == layout.crPlane && sideBySide)
            layout.pairOffset = std::min(layout.cbOffset, layout.crOffset);
    }
    return layout;
}

void FrameCoverageSink::setFrame(const FrameView &frame)
{
    assert(frame.format && frame.format->fourcc == format_->fourcc);
    frame_ = frame;
    rowBytes_ = format_->minStride(0, frame.width);
    if (alpha_.size() < frame.width + 17)
        alpha_.resize(frame.width + 17);
    // An item left without end() must not leak its opacity into this frame's chroma.
    for (const Interval &interval : intervals_)
        std::fill(alphaSums_.begin() + interval.g0, alphaSums_.begin() + interval.g1, 0);
    intervals_.clear();
    nextInterval_ = 0;
    pendingChromaRow_ = -1;
    // One luma row of at most one interval per chroma group; accumulateAlpha adds eight groups at a time.
    const size_t groups = (frame.width + 1) / 2;
    if (layout_.chroma && alphaSums_.size() < groups + 16) {
        alphaSums_.assign(groups + 16, 0);
        intervals_.reserve(groups);
    }
}

void FrameCoverageSink::begin(Rgba colour)
{
    colour_ = ItemColour{};
    colour_.alpha = colour.a;
    if (layout_.rgb) {
        colour_.rgb[format_->rOffset] = colour.r, colour_.rgbMask[format_->rOffset] = 0xff;
        colour_.rgb[format_->gOffset] = colour.g, colour_.rgbMask[format_->gOffset] = 0xff;
        colour_.rgb[format_->bOffset] = colour.b, colour_.rgbMask[format_->bOffset] = 0xff;
        if (format_->aOffset != kNoComponent)
            colour_.rgb[format_->aOffset] = 255, colour_.rgbMask[format_->aOffset] = 0xff;
        return;
    }
    // One fully opaque pixel through the encoder; every opacity is then a scaling of these codes.
    PremultipliedSum opaque;
    const uint8_t pixel[4] = {colour.r, colour.g, colour.b, 255};
    opaque.add(pixel);
    const YcbcrBlendSamples samples = encoder_.encode(opaque);
    colour_.luma = samples.y.value, colour_.cb = samples.cb.value, colour_.cr = samples.cr.value;
    // The chroma byte at the lower offset of a macropixel comes first (YUYV, UYVY, NV12: Cb; YVYU, NV21: Cr).
    const bool cbFirst = format_->cbOffset < format_->crOffset;
    colour_.pairCodes[0] = cbFirst ? colour_.cb : colour_.cr;
    colour_.pairCodes[1] = cbFirst ? colour_.cr : colour_.cb;
    for (unsigned k = 0; k < 8; ++k)
        colour_.packedChroma[k] = uint16_t(colour_.pairCodes[k % 2]);
}

void FrameCoverageSink::stage(const uint8_t *coverage, unsigned count, uint8_t *alpha) const
{
    alpha[-1] = 0;
    std::fill_n(alpha + count, 16, uint8_t(0));
    if (colour_.alpha == 255) {
        // Most runs are a few pixels: 8, 4, 2 and 1 byte copies instead of a call to memcpy.
        if (count > 32) {
            std::copy_n(coverage, count, alpha);
            return;
        }
        unsigned i = 0;
        for (; i + 8 <= count; i += 8)
            __builtin_memcpy(alpha + i, coverage + i, 8);
        if (i + 4 <= count)
            __builtin_memcpy(alpha + i, coverage + i, 4), i += 4;
        if (i + 2 <= count)
            __builtin_memcpy(alpha + i, coverage + i, 2), i += 2;
        if (i < count)
            alpha[i] = coverage[i];
        return;
    }
    const unsigned a = colour_.alpha;
    for (unsigned i = 0; i < count; ++i)
        alpha[i] = uint8_t(div255(coverage[i] * a));
}

void FrameCoverageSink::end()
{
    if (layout_.chroma)
        flushChroma();
}

} // namespace overlayd
