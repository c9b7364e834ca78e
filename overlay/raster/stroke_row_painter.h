// SPDX-License-Identifier: Apache-2.0
// StrokeRowPainter: the pixel work of StrokeRasterizer for one row. It takes the row's pixel runs of the stroke's
// segments, paints their coverage across the stroke into a row scratch (vector kernels for short and long runs, the
// exact per-pixel formula beside the ends), merges overlapping runs (max per pixel), trims zero ends and hands the
// row to the sink. The geometry (which segments cross a row, and where) is the rasterizer's; the types both share
// are defined here, with the coverage profile they are painted with.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>

#include "overlay/raster/coverage.h"
#include "overlay/raster/coverage_sink.h"

namespace overlayd {

// Bytes of slack after a row of the painter's scratch: its vector loops write up to this far past a run, and a
// sink may read as far (rowRuns' contract).
inline constexpr int kStrokeRowSlack = 16;
static_assert(kStrokeRowSlack >= kCoverageReadAhead, "rowRuns() promises sinks kCoverageReadAhead readable bytes");

class StrokeRowPainter
{
public:
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

    // The stroke's profile for `width` pixels (antialias off: coverage 0 or 255) and the clip (sink pixels) whose
    // rows are painted; the semantics are stroke_raster.cpp's.
    void setStroke(double width, bool antialias, const LayerRect &clip);
    const Profile &profile() const { return profile_; }
    // Grows the scratch (never shrinks it) for the clip's width and a row of up to `segments` runs.
    void reserve(size_t segments);
    // Paints the row's runs spans[0, count) (sorted by x0; spans[count] is idle) into the row scratch and hands
    // them to the sink in one rowRuns() call; each run points into the scratch, readable kStrokeRowSlack bytes past
    // its last pixel.
    void emitRow(int y, const Span *spans, size_t count, CoverageSink &sink);

private:
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
    // Scratch reused between calls so that a redraw does not allocate.
    std::vector<uint8_t> row_;
    // The current row's runs, pointing into row_; sized once a call to the segment count (a row has at most one
    // run per segment), so that a run is written through a pointer without a capacity check.
    std::vector<CoverageRun> rowRuns_;
};

} // namespace overlayd
