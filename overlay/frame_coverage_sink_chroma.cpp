// FrameCoverageSink's chroma bookkeeping: which groups of the pending chroma row an item touched, and the flush that
// blends each touched sample once with the item's mean opacity over its macropixel.
#include "overlay/frame_coverage_sink.h"

#include <algorithm>

namespace overlayd {

void FrameCoverageSink::noteChroma(unsigned y, unsigned x0, unsigned count)
{
    const int chromaRow = int(y / layout_.vSub);
    if (chromaRow != pendingChromaRow_) {
        flushChroma();
        pendingChromaRow_ = chromaRow;
        lastLumaRow_ = int(y);
        secondRowStart_ = 0;
    } else if (int(y) != lastLumaRow_) {
        lastLumaRow_ = int(y);
        secondRowStart_ = intervals_.size();
    }
    // Within one luma row the calls come in increasing x, so a new interval can only touch the previous one.
    const Interval next{x0 / 2, (x0 + count + 1) / 2};
    if (intervals_.size() > secondRowStart_ && next.g0 <= intervals_.back().g1)
        intervals_.back().g1 = std::max(intervals_.back().g1, next.g1);
    else
        intervals_.push_back(next);
}

// The two luma rows of a 4:2:0 chroma row each give sorted, disjoint intervals; merging them keeps every sample to
// one blend without sorting.
const std::vector<FrameCoverageSink::Interval> &FrameCoverageSink::mergedIntervals()
{
    if (secondRowStart_ == 0 || secondRowStart_ == intervals_.size())
        return intervals_;
    merged_.clear();
    size_t a = 0, b = secondRowStart_;
    while (a < secondRowStart_ || b < intervals_.size()) {
        const bool takeA = b == intervals_.size() || (a < secondRowStart_ && intervals_[a].g0 <= intervals_[b].g0);
        const Interval next = takeA ? intervals_[a++] : intervals_[b++];
        if (!merged_.empty() && next.g0 <= merged_.back().g1)
            merged_.back().g1 = std::max(merged_.back().g1, next.g1);
        else
            merged_.push_back(next);
    }
    return merged_;
}

void FrameCoverageSink::flushChroma()
{
    if (pendingChromaRow_ < 0)
        return;
    for (const Interval &interval : mergedIntervals())
        blendChromaInterval(unsigned(pendingChromaRow_), interval);
    intervals_.clear();
    pendingChromaRow_ = lastLumaRow_ = -1;
    secondRowStart_ = 0;
}

void FrameCoverageSink::blendChromaInterval(unsigned chromaRow, Interval interval)
{
    const PlaneView &cbPlane = frame_.planes[layout_.cbPlane], &crPlane = frame_.planes[layout_.crPlane];
    const unsigned step = layout_.chromaStep;
    uint8_t *cb = cbPlane.data + size_t(chromaRow) * cbPlane.stride + layout_.cbOffset + interval.g0 * step;
    uint8_t *cr = crPlane.data + size_t(chromaRow) * crPlane.stride + layout_.crOffset + interval.g0 * step;
    uint16_t *sums = alphaSums_.data() + interval.g0;
    // A macropixel averages the pixels that exist: a sum over 2 x rows pixels scales to four pixels' worth by
    // 2 - rows bits, one more for the single-pixel column at an odd right edge.
    const unsigned rows = std::min(layout_.vSub, frame_.height - chromaRow * layout_.vSub);
    const unsigned shift = 2 - rows;
    const bool oddEdge = frame_.width % 2 == 1 && interval.g1 == (frame_.width + 1) / 2;
    const unsigned whole = interval.g1 - interval.g0 - (oddEdge ? 1 : 0);
    blendChroma(cb, cr, step, sums, whole, shift, colour_);
    if (oddEdge)
        blendChroma(cb + whole * step, cr + whole * step, step, sums + whole, 1, shift + 1, colour_);
}

} // namespace overlayd
