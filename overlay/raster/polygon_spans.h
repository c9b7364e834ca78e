// SPDX-License-Identifier: Apache-2.0
// Polygon spans: which whole pixels a filled polygon covers, as runs per row -- the privacy masks' raster. A pixel
// is inside when its centre is (the nonzero winding rule, so a self-crossing outline leaves no hole); rows can be
// widened to whole macropixels so that no chroma sample is shared with a pixel outside.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace overlayd {

// Pixels [x0, x1) of row y.
struct RowSpan {
    int y = 0, x0 = 0, x1 = 0;
};

// A set of pixels as sorted, disjoint spans with an index by row.
class SpanRows
{
public:
    SpanRows() = default;
    // spans in any order, overlapping or not; each is cut to the frame, widened to whole groups of hSub columns and
    // vSub rows counted from the frame's origin (1, 1: as they are), and merged.
    SpanRows(std::vector<RowSpan> spans, unsigned width, unsigned height, unsigned hSub = 1, unsigned vSub = 1);

    std::span<const RowSpan> row(unsigned y) const
    {
        return y + 1 < rowStart_.size() ? std::span(spans_).subspan(rowStart_[y], rowStart_[y + 1] - rowStart_[y])
                                        : std::span<const RowSpan>();
    }
    const std::vector<RowSpan> &spans() const { return spans_; }
    bool empty() const { return spans_.empty(); }
    // Pixels covered.
    uint64_t area() const;

private:
    std::vector<RowSpan> spans_;
    std::vector<uint32_t> rowStart_; // height + 1 entries
};

// Appends the spans of the polygon (pixel coordinates, memory order; pixel (x, y) has its centre at x + 0.5,
// y + 0.5) within [0, width) x [0, height), row by row. Coordinates beyond +-1e7 are clamped first.
void polygonSpans(std::span<const glm::dvec2> polygon, int width, int height, std::vector<RowSpan> &out);

} // namespace overlayd
