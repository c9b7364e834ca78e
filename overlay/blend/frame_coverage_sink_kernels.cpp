// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink's row paths: row() and rowRuns() (a thin line's run unstaged when the producer's row may be read
// past it), packed 4:2:2 rows, luma with planar or semi-planar chroma, RGB; the pixel steps are in sink_steps.h
// (built with -O3).
#include "overlay/blend/frame_coverage_sink.h"

#include "overlay/blend/sink_lanes.h"
#include "overlay/blend/sink_steps.h"

#include <algorithm>
#include <cassert>

namespace overlayd {

using namespace sink_lanes;
using namespace sink_steps;

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
