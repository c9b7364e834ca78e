// FrameCoverageSink's chroma: a 4:2:0 chroma row's groups blended once each, when its last luma row has added its
// opacity (or the item leaves the row), with the item's mean opacity over each macropixel.
#include "overlay/frame_coverage_sink.h"

#include <algorithm>

namespace overlayd {

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
    while (next < intervals_.size() && intervals_[next].g1 <= groups.g0)
        blendChromaInterval(chromaRow, intervals_[next++]);
    Interval span = groups;
    if (next < intervals_.size() && intervals_[next].g0 < groups.g0)
        span.g0 = intervals_[next].g0;
    while (next < intervals_.size() && intervals_[next].g1 <= groups.g1)
        ++next;
    if (next < intervals_.size() && intervals_[next].g0 < groups.g1)
        intervals_[next].g0 = groups.g1;
    blendChromaInterval(chromaRow, span);
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
    const unsigned whole = interval.g1 - interval.g0 - (oddEdge ? 1 : 0), room = (frame_.width + 1) / 2 - interval.g0;
    blendChroma(cb, cr, step, sums, whole, room, shift, colour_);
    if (oddEdge)
        blendChroma(cb + whole * step, cr + whole * step, step, sums + whole, 1, 1, shift + 1, colour_);
}

} // namespace overlayd
