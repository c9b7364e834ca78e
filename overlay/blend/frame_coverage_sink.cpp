// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink: set-up per frame and per item, and the staging of a row() call's opacities for the kernels. Luma
// (or RGB) bytes and 4:2:2 chroma blend as rows arrive; 4:2:0 chroma opacity is summed over both luma rows of a
// macropixel and each sample blended once, as its second row arrives. The whole file is a hot path, built with -O3;
// the pixel steps are in sink_steps.h and sink_lanes.h.
#include "overlay/blend/frame_coverage_sink.h"

#include <algorithm>
#include <cassert>

#include "overlay/blend/div255.h"
#include "overlay/blend/sink_lanes.h"
#include "overlay/blend/sink_steps.h"

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

// Chroma: a 4:2:0 chroma row's groups blended once each, when its last luma row has added its opacity (or the item
// leaves the row), with the item's mean opacity over each macropixel.

namespace {

template<unsigned Step>
void chromaLoop(uint8_t *__restrict cb, uint8_t *__restrict cr, uint16_t *__restrict sums, unsigned count,
                unsigned shift, unsigned cbCode, unsigned crCode)
{
    for (unsigned g = 0; g < count; ++g) {
        const unsigned sum4 = unsigned(sums[g]) << shift, alpha = meanAlpha(sum4);
        sums[g] = 0; // ready for the next chroma row
        const uint16_t keep = uint16_t(255 - alpha);
        cb[g * Step] = uint8_t(scaled(sum4, cbCode, alpha) + div255(uint16_t(cb[g * Step] * keep)));
        cr[g * Step] = uint8_t(scaled(sum4, crCode, alpha) + div255(uint16_t(cr[g * Step] * keep)));
    }
}

// NV12/NV21: eight groups' Cb/Cr pairs (16 bytes) blended by chromaLoop's rule from their four-pixel sums.
inline void blendEightPairs(uint8_t *pairs, Words8 sum4, unsigned firstCode, unsigned secondCode)
{
    // Each 16-bit word is one group's pair: the first sample in its low byte, the second in its high byte.
    Words8 words;
    __builtin_memcpy(&words, pairs, 16);
    const Words8 alpha = meanAlpha8(sum4), keep = 255 - alpha;
    const Words8 first =
        scaledBySum(sum4, Words8{} + uint16_t(firstCode), alpha) + div255(Words8((words & 0xff) * keep));
    const Words8 second =
        scaledBySum(sum4, Words8{} + uint16_t(secondCode), alpha) + div255(Words8((words >> 8) * keep));
    words = first | (second << 8);
    __builtin_memcpy(pairs, &words, 16);
}

// NV12/NV21: count (< 8) groups' pairs as one eight-group step, the other lanes' sums held back (opacity 0 leaves a
// byte as it is); the row must have eight groups from pairs.
inline void blendFewPairs(uint8_t *pairs, uint16_t *sums, unsigned count, unsigned shift, unsigned firstCode,
                          unsigned secondCode)
{
    static constexpr Words8 kLane = {0, 1, 2, 3, 4, 5, 6, 7};
    Words8 sum;
    __builtin_memcpy(&sum, sums, 16);
    const Words8 mine = kLane < uint16_t(count) ? sum : 0, others = sum - mine;
    __builtin_memcpy(sums, &others, 16);
    blendEightPairs(pairs, mine << shift, firstCode, secondCode);
}

// NV12/NV21: Cb and Cr interleaved in one plane, eight groups (16 bytes) per step, the last few by blendFewPairs
// when the row has room (in groups from pairs) for it, else by chromaLoop's scalar rule. Sums are zeroed as they
// are used.
void chromaInterleaved(uint8_t *pairs, uint16_t *sums, unsigned count, unsigned room, unsigned shift,
                       unsigned firstCode, unsigned secondCode)
{
    unsigned g = 0;
    for (; g + 8 <= count; g += 8) {
        Words8 sum;
        __builtin_memcpy(&sum, sums + g, 16);
        __builtin_memset(sums + g, 0, 16);
        blendEightPairs(pairs + 2 * g, sum << shift, firstCode, secondCode);
    }
    if (g == count)
        return;
    if (g + 8 <= room)
        return blendFewPairs(pairs + 2 * g, sums + g, count - g, shift, firstCode, secondCode);
    chromaLoop<2>(pairs + 2 * g, pairs + 2 * g + 1, sums + g, count - g, shift, firstCode, secondCode);
}

} // namespace

void FrameCoverageSink::blendChroma(uint8_t *cb, uint8_t *cr, unsigned step, uint16_t *sums, unsigned count,
                                    unsigned shift, const ItemColour &colour)
{
    // Packed 4:2:2 keeps Cb and Cr in one plane, 2 bytes apart: the loops never write the same byte through both.
    // (Cb and Cr side by side, NV12/NV21/NV16, go to chromaInterleaved: blendChromaRange.)
    if (step == 1)
        chromaLoop<1>(cb, cr, sums, count, shift, colour.cb, colour.cr);
    else if (step == 2)
        chromaLoop<2>(cb, cr, sums, count, shift, colour.cb, colour.cr);
    else
        chromaLoop<4>(cb, cr, sums, count, shift, colour.cb, colour.cr);
}

// A macropixel averages the pixels that exist: a sum over 2 x rows pixels scales to four pixels' worth by 2 - rows
// bits (one more for the single-pixel column at an odd right edge).
inline unsigned FrameCoverageSink::chromaShift(unsigned chromaRow) const
{
    return 2 - std::min(layout_.vSub, frame_.height - chromaRow * layout_.vSub);
}

inline uint8_t *FrameCoverageSink::pairRow(unsigned chromaRow) const
{
    const PlaneView &plane = frame_.planes[layout_.cbPlane];
    return plane.data + size_t(chromaRow) * plane.stride + layout_.pairOffset;
}

// The usual NV12/NV21/NV16 interval, a thin line's few groups away from the right edge, in one step, inline; any other
// by blendChromaRange.
inline void FrameCoverageSink::blendChromaInterval(unsigned chromaRow, Interval interval)
{
    if (layout_.pairOffset == kNoPairs || interval.g1 - interval.g0 >= 8 || interval.g0 + 8 > frame_.width / 2)
        return blendChromaRange(chromaRow, interval);
    blendFewPairs(pairRow(chromaRow) + 2 * interval.g0, alphaSums_.data() + interval.g0, interval.g1 - interval.g0,
                  chromaShift(chromaRow), colour_.pairCodes[0], colour_.pairCodes[1]);
}

void FrameCoverageSink::flushChroma()
{
    if (pendingChromaRow_ < 0)
        return;
    for (size_t i = nextInterval_; i < intervals_.size(); ++i)
        blendChromaInterval(unsigned(pendingChromaRow_), intervals_[i]);
    intervals_.clear();
    nextInterval_ = 0;
    pendingChromaRow_ = -1;
}

// Both rows come in increasing x, so one pass over the first row's intervals meets each run of the last row:
// intervals wholly to its left are final and blended on the way, one overlapping its left end joins its blend,
// the part of one reaching past its right end waits for the next run (which may share those groups).
void FrameCoverageSink::blendLastRowGroups(unsigned chromaRow, Interval groups)
{
    if (int(chromaRow) != pendingChromaRow_)
        return blendChromaInterval(chromaRow, groups);
    size_t &next = nextInterval_;
    Interval span = groups;
    for (; next < intervals_.size() && intervals_[next].g1 <= groups.g0; ++next) {
        // Final: no later run of the last row reaches left of this one. One within eight groups of the run's end
        // joins its blend (the groups between hold no opacity and keep their bytes).
        if (intervals_[next].g0 + 8 > groups.g1)
            span.g0 = std::min(span.g0, intervals_[next].g0);
        else
            blendChromaInterval(chromaRow, intervals_[next]);
    }
    if (next < intervals_.size() && intervals_[next].g0 < groups.g0)
        span.g0 = std::min(span.g0, intervals_[next].g0);
    while (next < intervals_.size() && intervals_[next].g1 <= groups.g1)
        ++next;
    if (next < intervals_.size() && intervals_[next].g0 < groups.g1)
        intervals_[next].g0 = groups.g1;
    blendChromaInterval(chromaRow, span);
}

void FrameCoverageSink::blendChromaRange(unsigned chromaRow, Interval interval)
{
    const unsigned shift = chromaShift(chromaRow);
    uint16_t *sums = alphaSums_.data() + interval.g0;
    const bool oddEdge = frame_.width % 2 == 1 && interval.g1 == (frame_.width + 1) / 2;
    const unsigned whole = interval.g1 - interval.g0 - (oddEdge ? 1 : 0), room = (frame_.width + 1) / 2 - interval.g0;
    if (layout_.pairOffset != kNoPairs) {
        uint8_t *pairs = pairRow(chromaRow) + 2 * interval.g0;
        const unsigned first = colour_.pairCodes[0], second = colour_.pairCodes[1];
        chromaInterleaved(pairs, sums, whole, room, shift, first, second);
        if (oddEdge)
            chromaInterleaved(pairs + 2 * whole, sums + whole, 1, 1, shift + 1, first, second);
        return;
    }
    const PlaneView &cbPlane = frame_.planes[layout_.cbPlane], &crPlane = frame_.planes[layout_.crPlane];
    const unsigned step = layout_.chromaStep;
    uint8_t *cb = cbPlane.data + size_t(chromaRow) * cbPlane.stride + layout_.cbOffset + interval.g0 * step;
    uint8_t *cr = crPlane.data + size_t(chromaRow) * crPlane.stride + layout_.crOffset + interval.g0 * step;
    blendChroma(cb, cr, step, sums, whole, shift, colour_);
    if (oddEdge)
        blendChroma(cb + whole * step, cr + whole * step, step, sums + whole, 1, shift + 1, colour_);
}

// The row paths: row() and rowRuns() (a thin line's run unstaged when the producer's row may be read past it),
// packed 4:2:2 rows, luma with planar or semi-planar chroma, RGB.

void FrameCoverageSink::blendPackedRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    // Whole windows of four macropixels from the run's first, as long as they end inside the row and before a
    // one-pixel macropixel at an odd right edge; the groups past the last window go the general way.
    const unsigned g0 = unsigned(x0) / 2, gEnd = unsigned(x0 + count + 1) / 2, wholeGroups = frame_.width / 2;
    const unsigned windows = std::min((gEnd - g0 + 3) / 4, (wholeGroups - std::min(g0, wholeGroups)) / 4);
    const uint8_t *pixels = alpha - x0 % 2; // staged: the pixel before an odd x0 reads 0
    for (unsigned w = 0; w < windows; ++w, pixels += 8)
        blendPackedWindow(row + size_t(g0 + 4 * w) * 4, eightOpacities(pixels), colour_.packedChroma, colour_.luma,
                          layout_.lumaOffset);
    const int rest = std::max(x0, int(2 * (g0 + 4 * windows)));
    if (rest >= x0 + count)
        return;
    const int done = rest - x0;
    blendLuma(row + size_t(rest) * 2, layout_, alpha + done, unsigned(count - done), colour_.luma,
              rowBytes_ - size_t(rest) * 2);
    accumulateAlpha(alphaSums_.data(), unsigned(rest), alpha + done, unsigned(count - done));
    blendChromaRange(unsigned(y), {unsigned(rest) / 2, gEnd});
}

void FrameCoverageSink::accumulateAlpha(uint16_t *sums, unsigned x0, const uint8_t *alpha, unsigned count)
{
    // Sixteen pixels (eight groups) a step from the first group's first pixel: alpha is staged, so the pixel before
    // an odd x0 and the 16 after the last read 0, and sums has slack for the eight groups past the last.
    const uint8_t *pixels = alpha - x0 % 2;
    uint16_t *group = sums + x0 / 2;
    for (unsigned i = 0; i < x0 % 2 + count; i += 16, pixels += 16, group += 8) {
        Words8 pairs;
        __builtin_memcpy(&pairs, pixels, 16);
        addGroupSums(group, pairs);
    }
}

inline int FrameCoverageSink::enterChromaRow(int y)
{
    const int chromaRow = y >> (layout_.vSub - 1); // vSub is 1 or 2: no division per call
    if (chromaRow != pendingChromaRow_)
        flushChroma();
    return chromaRow;
}

// A chroma row's opacities add up in alphaSums_ until its last luma row: the first row's groups wait in intervals_,
// the last row's are blended as they come, with the waiting ones beside them.
inline void FrameCoverageSink::addChromaGroups(int y, int chromaRow, Interval groups)
{
    if (((y + 1) & int(layout_.vSub - 1)) == 0 || unsigned(y + 1) == frame_.height) {
        blendLastRowGroups(unsigned(chromaRow), groups);
        return;
    }
    pendingChromaRow_ = chromaRow;
    intervals_.push_back(groups);
}

inline bool FrameCoverageSink::blendShortPacked(uint8_t *row, const CoverageRun &run) const
{
    // One window from the run's first macropixel, if the run fits in it and its four macropixels are whole ones
    // of the row.
    const unsigned x0 = unsigned(run.x0), count = unsigned(run.count), parity = x0 % 2, g0 = x0 / 2;
    if (parity + count > 8 || g0 + 4 > frame_.width / 2)
        return false;
    const uint64_t coverage = shortCoverage(run.coverage, count) << (8 * parity);
    blendPackedWindow(row + size_t(g0) * 4, wordLanes(opacities(coverage, colour_.alpha)), colour_.packedChroma,
                      colour_.luma, layout_.lumaOffset);
    return true;
}

inline bool FrameCoverageSink::blendShortYuv(uint8_t *row, int y, const CoverageRun &run)
{
    const unsigned x0 = unsigned(run.x0), count = unsigned(run.count), parity = x0 % 2;
    if (parity + count > 8 || !layout_.byteLuma || rowBytes_ - x0 < 8)
        return false;
    const uint64_t alpha = opacities(shortCoverage(run.coverage, count), colour_.alpha);
    lumaEight(row + x0, wordLanes(alpha), colour_.luma);
    if (!layout_.chroma)
        return true;
    const int chromaRow = enterChromaRow(y);
    // The run's (at most four) groups' opacity sums, added in one step: a 16-bit word of the bytes from the first
    // group's first pixel holds one group's two opacities.
    addGroupSums(alphaSums_.data() + x0 / 2, (Words8)Longs2{alpha << (8 * parity), 0});
    addChromaGroups(y, chromaRow, {x0 / 2, (x0 + count + 1) / 2});
    return true;
}

inline void FrameCoverageSink::blendRuns(int y, const CoverageRun *runs, size_t count, bool readAhead)
{
    const PlaneView &plane = frame_.planes[0];
    uint8_t *const row = plane.data + size_t(y) * plane.stride;
    uint8_t *const alpha = alpha_.data() + 1;
    for (size_t i = 0; i < count; ++i) {
        const CoverageRun &run = runs[i];
        if (run.count <= 0)
            continue;
        if (readAhead && (layout_.packed422 ? blendShortPacked(row, run) : blendShortYuv(row, y, run)))
            continue;
        stage(run.coverage, unsigned(run.count), alpha);
        if (layout_.packed422)
            blendPackedRow(row, y, run.x0, alpha, run.count);
        else if (layout_.rgb)
            blendRgb(row + size_t(run.x0) * layout_.pixelBytes, layout_.pixelBytes, alpha, unsigned(run.count),
                     colour_);
        else
            blendYuvRow(row, y, run.x0, alpha, run.count);
    }
}

void FrameCoverageSink::row(int y, int x0, const uint8_t *coverage, int count)
{
    const CoverageRun run{x0, count, coverage};
    blendRuns(y, &run, 1, false);
}

void FrameCoverageSink::rowRuns(int y, const CoverageRun *runs, size_t count)
{
    blendRuns(y, runs, count, true);
}

// Luma (or GREY) and planar or semi-planar chroma of one row() call.
void FrameCoverageSink::blendYuvRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    const size_t start = size_t(x0) * layout_.lumaStep;
    if (layout_.byteLuma && count <= 8 && rowBytes_ - start >= 8) // the usual thin-line run: 8 lanes, inline
        lumaEight(row + start, eightOpacities(alpha), colour_.luma);
    else
        blendLuma(row + start, layout_, alpha, unsigned(count), colour_.luma, rowBytes_ - start);
    if (!layout_.chroma)
        return;
    const int chromaRow = enterChromaRow(y);
    accumulateAlpha(alphaSums_.data(), unsigned(x0), alpha, unsigned(count));
    addChromaGroups(y, chromaRow, {unsigned(x0) / 2, unsigned(x0 + count + 1) / 2});
}

void FrameCoverageSink::blendLuma(uint8_t *pixels, const Layout &layout, const uint8_t *alpha, unsigned count,
                                  unsigned value, size_t room)
{
    const unsigned step = layout.lumaStep;
    assert(step == 1 || step == 2);
    // A long run (a flat line near the camera) as whole 16-byte vectors too, then its remainder.
    const unsigned perVector = 16 / step;
    while (count > perVector && room >= 32) {
        lumaShort(pixels, step, layout.lumaOffset, alpha, value);
        pixels += 16, room -= 16, alpha += perVector, count -= perVector;
    }
    if (count * step <= 16 && room >= 16)
        return lumaShort(pixels, step, layout.lumaOffset, alpha, value);
    uint8_t *dst = pixels + layout.lumaOffset;
    if (step == 1)
        lumaLoop<1>(dst, alpha, count, value);
    else
        lumaLoop<2>(dst, alpha, count, value);
}

void FrameCoverageSink::blendRgb(uint8_t *dst, unsigned pixelBytes, const uint8_t *alpha, unsigned count,
                                 const ItemColour &colour)
{
    assert(pixelBytes == 3 || pixelBytes == 4);
    if (pixelBytes == 3)
        rgbLoop<3>(dst, alpha, count, colour.rgb, colour.rgbMask);
    else
        rgbLoop<4>(dst, alpha, count, colour.rgb, colour.rgbMask);
}

} // namespace overlayd
