// SPDX-License-Identifier: Apache-2.0
// StrokeRasterizer: anti-aliased coverage of stroked polylines computed per pixel from its distance to the stroke
// (no full-frame mask): the cost follows the pixels covered, so a moving camera can redraw every frame.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "overlay/raster/coverage.h"
#include "overlay/raster/coverage_sink.h"
#include "overlay/raster/stroke_row_painter.h"
#include "projection/polylines.h"

namespace overlayd {

class StrokeRasterizer
{
public:
    // Emits, through sink.rowRuns() only (the caller calls begin/end), the coverage of every polyline of `lines`
    // stroked `width` pixels wide, united (max) over the whole set so that crossings and joints never count
    // twice. Points are in frame pixels with pixel centres at integers (OpenCV's convention); `origin` is the frame
    // pixel of the sink's pixel (0, 0); nothing is emitted outside `clip` (sink pixels). Ends are butt, joints
    // round. antialias off gives coverage 0 or 255. Every run's coverage pointer stays readable for
    // kStrokeRowSlack bytes past the run's last pixel (it points into the row scratch, which has that slack), so
    // that a sink may load whole vectors past a run's end.
    void rasterize(const Polylines &lines, double width, bool antialias, glm::dvec2 origin, const LayerRect &clip,
                   CoverageSink &sink);

private:
    using Floats4 = StrokeRowPainter::Floats4;
    using Doubles2 = StrokeRowPainter::Doubles2;
    using Segment = StrokeRowPainter::Segment;
    using Span = StrokeRowPainter::Span;
    static constexpr int kIdle = StrokeRowPainter::kIdle;

    void addPolyline(std::span<const glm::dvec2> points, glm::dvec2 origin);
    void addRun();
    void addSegment(glm::dvec2 a, glm::dvec2 b, bool roundStart, bool roundEnd);
    void sweep(CoverageSink &sink);
    // This row's run of g (false: none) into span.x0 and x1, and span.fast and s0 (y: the row).
    bool rowSpan(const Segment &g, double y, Span &span) const;
    StrokeRowPainter painter_;
    LayerRect clip_;
    double minX_ = 0, minY_ = 0, maxX_ = 0, maxY_ = 0; // the clip expanded by the reach: segments are cut to it
    Doubles2 runMin_{}, runMax_{};                     // the clamps of a run's ends (clip x) as {x0, -x1}
    Doubles2 slacks_{};                                // kSlack in both lanes
    // Scratch reused between calls so that a redraw does not allocate.
    std::vector<glm::dvec2> run_;
    std::vector<Segment> segments_;
    std::vector<Span> active_; // the segments crossing the current row, with their runs in it, in x order
};

} // namespace overlayd
