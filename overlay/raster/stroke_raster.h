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
#include "projection/polylines.h"

namespace overlayd {

// Bytes of slack after a row of the rasterizer's scratch: its vector loops write up to this far past a run, and a
// sink may read as far (rowRuns' contract).
inline constexpr int kStrokeRowSlack = 16;
static_assert(kStrokeRowSlack >= kCoverageReadAhead, "rowRuns() promises sinks kCoverageReadAhead readable bytes");

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
    // 4 float lanes (GCC/Clang vector extensions): the pixel kernels' constants are kept broadcast.
    using Floats4 [[gnu::vector_size(16)]] = float;
    // 2 double lanes: a run's two ends are computed side by side (SSE2's packed doubles, NEON's on arm64).
    using Doubles2 [[gnu::vector_size(16)]] = double;
    // How coverage falls off with the distance d (pixels) from the centre line, in 0..255 units:
    // clamp(gain * (reach - d), 0, peak); a binary profile is 255 where d <= reach. `extension` is how far a butt
    // end's coverage reaches past the end point (0.5 px anti-aliased, 0 binary). The kernels take -gain, reach, peak
    // (rounded to an integer) and 0.5 as float lanes.
    struct Profile {
        float gain = 255.0f, peak = 255.0f;
        double reach = 0.0, extension = 0.0;
        bool binary = false;
        Floats4 negGainLanes{}, reachLanes{}, peakLanes{}, halfLanes{};
    };
    // One segment, clipped, in sink pixels; t runs along it from a (0) to its length, s across it. The x extent
    // (from a.x) of its body in row y is [tLoX + tSlope * (y - a.y), tHiX + tSlope * (y - a.y)] for the band of t,
    // intersected with the same for the band of s; round ends add their discs. innerLo..innerHi is the band of t
    // where |s| alone decides the coverage (past neither a butt end's ramp nor a round end); dsLanes is the step
    // of s per pixel (-u.y) as the kernels take it.
    struct Segment {
        glm::dvec2 a, b, u;
        double length;
        bool roundStart, roundEnd;
        bool plain;      // neither end round nor the segment axis-aligned: its rows are the body's band alone
        int top, bottom; // rows it may cover, inside the clip
        double safeTop, safeBottom; // rows whose runs lie between the ends by a margin (rowSpan's shortcut)
        double tLoX, tHiX, tSlope, sLoX, sHiX, sSlope;
        double bodyY0, bodyY1; // rows of the body when a slab does not depend on x (axis-aligned segments)
        double innerLo, innerHi;
        Floats4 dsLanes;
        Floats4 laneSteps[2]; // {0, 1, 2, 3} * dsLanes and {4, 5, 6, 7} * dsLanes: the short step's lane * ds
        // The same numbers as lane pairs {low end, -high end} (negating is exact: one max gives both ends of a
        // run), and the two rows of the (t, s) rotation, {u.y, u.x} and {u.x, -u.y}.
        Doubles2 tEnds, tSlopes, sEnds, sSlopes, xEnds, tsFromY, tsFromX;
    };
    // A pixel run [x0, x1] (inclusive, sink pixels) of one segment in the current row; an active segment without
    // one in this row has x0 = kIdle, which sorts it after the runs. `fast`: the run can be painted by the short
    // kernel's inlined step (at most 8 pixels, anti-aliased, between the segment's ends), from s0, the distance
    // across at x0 as a float; both are derived where the run is (the sweep has the row's numbers at hand).
    struct Span {
        int x0, x1;
        const Segment *segment;
        float s0;
        bool fast;
    };
    static constexpr int kIdle = std::numeric_limits<int>::max();

    void addPolyline(std::span<const glm::dvec2> points, glm::dvec2 origin);
    void addRun();
    void addSegment(glm::dvec2 a, glm::dvec2 b, bool roundStart, bool roundEnd);
    void sweep(CoverageSink &sink);
    // This row's run of g (false: none) into span.x0 and x1, and span.fast and s0 (y: the row).
    bool rowSpan(const Segment &g, double y, Span &span) const;
    // Paints the row's runs spans[0, count) (sorted by x0; spans[count] is idle) into the row scratch and hands
    // them to the sink in one rowRuns() call; each run points into the scratch, readable kStrokeRowSlack bytes past
    // its last pixel.
    void emitRow(int y, const Span *spans, size_t count, CoverageSink &sink);
    // Paints the overlapping or touching runs spans[0, count) into one scratch run from x0 and writes it at out
    // (which it returns advanced).
    CoverageRun *addMerged(int y, const Span *spans, size_t count, int x0, int x1, CoverageRun *out);
    // Writes the scratch run row[0, n) from x0, trimmed of its zero ends, at out (returned advanced).
    static CoverageRun *addTrimmed(int x0, const uint8_t *row, int n, CoverageRun *out);
    // Max-es the segment's coverage of pixels [x0, x0 + count) of row y into out, or writes it when `overwrite`.
    void paint(const Segment &g, int y, int x0, int count, uint8_t *out, bool overwrite) const;
    uint8_t coverage(const Segment &g, double t, double s) const;

    Profile profile_;
    LayerRect clip_;
    double minX_ = 0, minY_ = 0, maxX_ = 0, maxY_ = 0; // the clip expanded by the reach: segments are cut to it
    Doubles2 runMin_{}, runMax_{};                     // the clamps of a run's ends (clip x) as {x0, -x1}
    Doubles2 slacks_{};                                // kSlack in both lanes
    // Scratch reused between calls so that a redraw does not allocate.
    std::vector<glm::dvec2> run_;
    std::vector<Segment> segments_;
    std::vector<Span> active_; // the segments crossing the current row, with their runs in it, in x order
    std::vector<uint8_t> row_;
    // The current row's runs, pointing into row_; sized once a call to the segment count (a row has at most one
    // run per segment), so that a run is written through a pointer without a capacity check.
    std::vector<CoverageRun> rowRuns_;
};

} // namespace overlayd
