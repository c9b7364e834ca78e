// StrokeRasterizer: anti-aliased coverage of stroked polylines computed per pixel from its distance to the stroke
// (no full-frame mask): the cost follows the pixels covered, so a moving camera can redraw every frame.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "overlay/coverage.h"
#include "overlay/coverage_sink.h"
#include "projection/polylines.h"

namespace overlayd {

// Bytes of slack after a row of the rasterizer's scratch: its vector loops write up to this far past a run.
inline constexpr int kStrokeRowSlack = 16;

class StrokeRasterizer
{
public:
    // Emits, through sink.row() only (the caller calls begin/end), the coverage of every polyline of `lines`
    // stroked `width` pixels wide, united (max) over the whole set so that crossings and joints never count
    // twice. Points are in frame pixels with pixel centres at integers (OpenCV's convention); `origin` is the frame
    // pixel of the sink's pixel (0, 0); nothing is emitted outside `clip` (sink pixels). Ends are butt, joints
    // round. antialias off gives coverage 0 or 255.
    void rasterize(const Polylines &lines, double width, bool antialias, glm::dvec2 origin, const LayerRect &clip,
                   CoverageSink &sink);

private:
    // 4 float lanes (GCC/Clang vector extensions): the pixel kernels' constants are kept broadcast.
    using Floats4 [[gnu::vector_size(16)]] = float;
    // How coverage falls off with the distance d (pixels) from the centre line, in 0..255 units:
    // clamp(gain * (reach - d), 0, peak); a binary profile is 255 where d <= reach. `extension` is how far a butt
    // end's coverage reaches past the end point (0.5 px anti-aliased, 0 binary). The kernels take gain, reach and
    // peak (rounded to an integer) as float lanes.
    struct Profile {
        float gain = 255.0f, peak = 255.0f;
        double reach = 0.0, extension = 0.0;
        bool binary = false;
        Floats4 gainLanes{}, reachLanes{}, peakLanes{};
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
        double tLoX, tHiX, tSlope, sLoX, sHiX, sSlope;
        double bodyY0, bodyY1; // rows of the body when a slab does not depend on x (axis-aligned segments)
        double innerLo, innerHi;
        Floats4 dsLanes;
    };
    // A pixel run [x0, x1] (inclusive, sink pixels) of one segment in the current row; an active segment without
    // one in this row has x0 = kIdle, which sorts it after the runs.
    struct Span {
        int x0, x1;
        const Segment *segment;
    };
    static constexpr int kIdle = std::numeric_limits<int>::max();

    void addPolyline(std::span<const glm::dvec2> points, glm::dvec2 origin);
    void addRun();
    void addSegment(glm::dvec2 a, glm::dvec2 b, bool roundStart, bool roundEnd);
    void sweep(CoverageSink &sink);
    bool rowSpan(const Segment &g, int y, Span &span) const;
    // Paints the row's runs spans[0, count) (sorted by x0) and hands them to the sink in one rowRuns() call.
    void emitRow(int y, const Span *spans, size_t count, CoverageSink &sink);
    // Paints the overlapping or touching runs spans[0, count) into one scratch run from x0 and adds it.
    void addMerged(int y, const Span *spans, size_t count, int x0, int x1);
    // Adds the scratch run row[0, n) from x0, trimmed of its zero ends.
    void addTrimmed(int x0, const uint8_t *row, int n);
    // Max-es the segment's coverage of pixels [x0, x0 + count) of row y into out, or writes it when `overwrite`.
    void paint(const Segment &g, int y, int x0, int count, uint8_t *out, bool overwrite) const;
    // paint(overwrite) for the usual run, at most 8 pixels between the segment's ends: false (nothing written)
    // for any other.
    bool paintShortRun(const Segment &g, int y, int x0, int count, uint8_t *out) const;
    uint8_t coverage(const Segment &g, double t, double s) const;

    Profile profile_;
    LayerRect clip_;
    double minX_ = 0, minY_ = 0, maxX_ = 0, maxY_ = 0; // the clip expanded by the reach: segments are cut to it
    double runX0Min_ = 0, runX0Max_ = 0, runX1Min_ = 0, runX1Max_ = 0; // the clamps of a run's ends (clip x)
    // Scratch reused between calls so that a redraw does not allocate.
    std::vector<glm::dvec2> run_;
    std::vector<Segment> segments_;
    std::vector<Span> active_; // the segments crossing the current row, with their runs in it, in x order
    std::vector<uint8_t> row_;
    std::vector<CoverageRun> rowRuns_; // the current row's runs, pointing into row_
};

} // namespace overlayd
