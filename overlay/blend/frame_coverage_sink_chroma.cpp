// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink's chroma: a 4:2:0 chroma row's groups blended once each, when its last luma row has added its
// opacity (or the item leaves the row), with the item's mean opacity over each macropixel.
#include "overlay/blend/frame_coverage_sink.h"

#include <algorithm>

#include "overlay/blend/div255.h"
#include "overlay/blend/sink_lanes.h"

namespace overlayd {

using namespace sink_lanes;

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

} // namespace overlayd
