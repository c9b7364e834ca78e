// FrameCoverageSink: per item, luma (or RGB) bytes blend as rows arrive; chroma opacity is summed per macropixel and
// blended when the item leaves a chroma row, so that a 4:2:0 sample sees both of its luma rows.
#include "overlay/frame_coverage_sink.h"

#include "overlay/div255.h"

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
    // Luma bytes sit at a fixed step in every YUV entry of the table (Y0 and Y1 of a group one pixel step apart).
    assert(layout.rgb || format.pixelsPerGroup == 1 || format.yOffset[1] == format.yOffset[0] + layout.lumaStep);
    layout.chroma = !layout.rgb && format.cbOffset != kNoComponent;
    if (layout.chroma) {
        assert(format.hSubSampling == 2 && format.vSubSampling <= 2);
        layout.chromaStep = format.planes[format.cbPlane].bytesPerGroup;
        layout.cbPlane = format.cbPlane, layout.crPlane = format.crPlane;
        layout.cbOffset = format.cbOffset, layout.crOffset = format.crOffset;
        layout.vSub = format.vSubSampling;
    }
    return layout;
}

void FrameCoverageSink::setFrame(const FrameView &frame)
{
    assert(frame.format && frame.format->fourcc == format_->fourcc);
    frame_ = frame;
    rowBytes_ = format_->minStride(0, frame.width);
    if (alpha_.size() < frame.width)
        alpha_.resize(frame.width);
    // An item left without end() must not leak its opacity into this frame's chroma.
    for (const Interval &interval : intervals_)
        std::fill(alphaSums_.begin() + interval.g0, alphaSums_.begin() + interval.g1, 0);
    intervals_.clear();
    pendingChromaRow_ = lastLumaRow_ = -1;
    // Two luma rows of at most one interval per chroma group each.
    const size_t groups = (frame.width + 1) / 2;
    if (layout_.chroma && alphaSums_.size() < groups + 1) {
        alphaSums_.assign(groups + 1, 0);
        intervals_.reserve(2 * groups);
        merged_.reserve(2 * groups);
    }
}

void FrameCoverageSink::begin(Rgba colour)
{
    previousY_ = -1;
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
}

const uint8_t *FrameCoverageSink::opacities(const uint8_t *coverage, unsigned count)
{
    if (colour_.alpha == 255)
        return coverage;
    const unsigned a = colour_.alpha;
    uint8_t *alpha = alpha_.data();
    for (unsigned i = 0; i < count; ++i)
        alpha[i] = uint8_t(div255(coverage[i] * a));
    return alpha;
}

void FrameCoverageSink::row(int y, int x0, const uint8_t *coverage, int count)
{
    if (count <= 0)
        return;
    prefetchAhead(y, x0, count);
    const uint8_t *alpha = opacities(coverage, unsigned(count));
    const PlaneView &plane = frame_.planes[0];
    uint8_t *row = plane.data + size_t(y) * plane.stride;
    if (layout_.rgb) {
        blendRgb(row + size_t(x0) * layout_.pixelBytes, layout_.pixelBytes, alpha, unsigned(count), colour_);
        return;
    }
    const size_t start = size_t(x0) * layout_.lumaStep;
    blendLuma(row + start, layout_, alpha, unsigned(count), colour_.luma, rowBytes_ - start);
    if (layout_.chroma) {
        noteChroma(unsigned(y), unsigned(x0), unsigned(count));
        accumulateAlpha(alphaSums_.data(), unsigned(x0), alpha, unsigned(count));
    }
}

// A stroke's rows arrive one below the other, each in a different page of a frame that is usually cold: the
// hardware prefetchers do not follow that, so we ask for the bytes a few rows down where the item's slope says it
// will be. Several misses then overlap instead of one per row.
void FrameCoverageSink::prefetchAhead(int y, int x0, int count)
{
    constexpr int kRowsAhead = 8;
    if (y == previousY_)
        return;
    const int slope = previousY_ == y - 1 ? x0 - previousX0_ : 0;
    previousY_ = y, previousX0_ = x0;
    prefetchRow(y + kRowsAhead, x0 + slope * kRowsAhead, count);
}

void FrameCoverageSink::prefetchRow(int y, int x0, int count)
{
    if (y >= int(frame_.height))
        return;
    // The guess is off by a few pixels where the slope is not a whole number of pixels per row: widen it.
    constexpr int kSlack = 6;
    const int first = std::clamp(x0 - kSlack, 0, int(frame_.width) - 1);
    const int last = std::clamp(x0 + count + kSlack, 1, int(frame_.width)) - 1;
    const PlaneView &luma = frame_.planes[0];
    const unsigned step = layout_.rgb ? layout_.pixelBytes : layout_.lumaStep;
    const uint8_t *row = luma.data + size_t(y) * luma.stride;
    __builtin_prefetch(row + size_t(first) * step, 1);
    __builtin_prefetch(row + size_t(last) * step, 1);
    if (!layout_.chroma || layout_.cbPlane == 0 || y % int(layout_.vSub) != 0)
        return; // packed 4:2:2 chroma shares the luma's bytes
    const size_t chromaRow = size_t(y) / layout_.vSub, chromaByte = size_t(first) / 2 * layout_.chromaStep;
    const PlaneView &cb = frame_.planes[layout_.cbPlane], &cr = frame_.planes[layout_.crPlane];
    __builtin_prefetch(cb.data + chromaRow * cb.stride + chromaByte, 1);
    if (layout_.crPlane != layout_.cbPlane)
        __builtin_prefetch(cr.data + chromaRow * cr.stride + chromaByte, 1);
}

void FrameCoverageSink::end()
{
    if (layout_.chroma)
        flushChroma();
}

} // namespace overlayd
