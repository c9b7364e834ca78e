// SPDX-License-Identifier: Apache-2.0
// StrokeRasterizer: stroked polylines -> coverage row by row, from each pixel's distance to the stroke.
//
// Semantics. Pixel centres are at integer coordinates (OpenCV's convention). A polyline of n points is n - 1
// segments; each is a capsule of half-width hw = width / 2 around its centre line, except at the polyline's two ends,
// which are butt (flat, not extended). Interior joints are round (the capsules' discs), so joints show no seam or
// notch; a closed loop (last point equal to the first) has no ends, its closing point is a joint too. Consecutive
// equal points are one point; a non-finite point ends the polyline before it and starts a new one after it.
// Coverage is a box-filter estimate from the distance d of the pixel centre to the centre line (or, past a round
// end, to the end point): clamp(hw + 0.5 - d, 0, 1); a butt end multiplies it by clamp(0.5 + t, 0, 1), t being how
// far the centre lies inside the end along the segment. Product rather than min: the box filter is separable, so
// for an axis-aligned stroke the product is the exact covered area at the corners too (min would give 0.5 where
// a corner pixel is a quarter covered). A straight stroke's coverage summed across it is its width exactly
// (width >= 1). Thinner strokes use a 1 px tent, width * clamp(1 - d, 0, 1), so a thin line keeps its total ink.
// Without anti-aliasing a pixel is 255 when its centre is inside: d <= max(hw, 0.5) and within the butt ends.
// Coverage is 0..255, rounded, and united over every polyline of the call by max per pixel.
//
// Speed. Segments are cut to the clip (expanded by the stroke's reach), sorted by first row and swept row by row
// with an active list: each active segment gives the pixel run where its capsule meets the row (linear in y, plus
// a square root near round ends); runs are sorted (kept in x order from row to row), merged and painted into a row
// scratch, max per pixel, by branch-free vector loops (no square root except beside round ends or butt-end ramps,
// which take a scalar formula). Most runs are a steep stroke's 3-6 pixels, so the cost per run is what counts:
// per-segment constants are derived once, the active list is updated in place (runs computed and insertion-sorted
// in one pass), a run's two ends are computed side by side in two double lanes (the high end negated, which is
// exact), a steep segment's middle rows (its "safe rows", where the band of t contains the band of s and every
// pixel lies between the ends with half a pixel to spare) skip the band of t and the end test, and a run that
// touches no other and lies between its segment's ends is written by one inlined step of the short kernel. Every
// shortcut evaluates the same expressions as the general path (or, in safe rows, skips a max and a test whose
// outcome is certain by far more than the rounding), so the bytes are the same.
// Cost: covered pixels plus rows spanned, whatever the bounding box; no allocation once the scratch has grown.
// Known limit: where two different segments each cover part of a pixel (a crossing's or a sharp joint's inner
// corner) the max is below the union's area.
#include "overlay/raster/stroke_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFlat = 1e-9;      // a direction component this small is 0 (never divided by)
constexpr double kSamePoint = 1e-9; // consecutive points closer than this (px) are one point
constexpr double kSlack = 1e-7;     // pixel runs widen by this so a centre exactly on a binary edge is evaluated
// A segment this steep (|u.y|) or steeper has safe rows: the t of its runs' pixels lies kSafeMargin px or more inside
// its ends. The expressions' rounding is far below that: coordinates are ints of the clip plus at most the reach
// (< 1e6), where a double's error is below 1e-9 px.
constexpr double kSteep = 0.25, kSafeMargin = 0.5;

// A run's two ends as ints: cvttpd2dq and back (SSE2), the vector counterpart of int(x) and double(int(x)).
using Ints2 [[gnu::vector_size(8)]] = int32_t;

bool finite(glm::dvec2 p)
{
    return std::isfinite(p.x) && std::isfinite(p.y);
}

// The x extent (relative to the segment's start) of the band lo <= dy * cy + x * cx <= hi in row dy, as
// [loX + slope * dy, hiX + slope * dy]; a band that does not depend on x limits the rows instead (y0..y1).
struct Band {
    double loX = -kInf, hiX = kInf, slope = 0.0, y0 = -kInf, y1 = kInf;
};

Band band(double cx, double cy, double lo, double hi)
{
    Band b;
    if (std::fabs(cx) > kFlat) {
        b.loX = (cx > 0 ? lo : hi) / cx;
        b.hiX = (cx > 0 ? hi : lo) / cx;
        b.slope = -cy / cx;
    } else {
        b.y0 = (cy > 0 ? lo : hi) / cy;
        b.y1 = (cy > 0 ? hi : lo) / cy;
    }
    return b;
}

} // namespace

void StrokeRasterizer::rasterize(const Polylines &lines, double width, bool antialias, glm::dvec2 origin,
                                 const LayerRect &clip, CoverageSink &sink)
{
    if (!(width > 0.0) || !std::isfinite(width) || clip.empty() || !finite(origin))
        return;
    painter_.setStroke(width, antialias, clip);
    const StrokeRowPainter::Profile &profile = painter_.profile();
    clip_ = clip;
    // x0 in [clip.x0, clip.x1], x1 in [clip.x0 - 1, clip.x1 - 1], the latter negated as the sweep carries it.
    runMin_ = Doubles2{double(clip.x0), -(clip.x1 - 1.0)};
    runMax_ = Doubles2{double(clip.x1), -(clip.x0 - 1.0)};
    slacks_ = Doubles2{kSlack, kSlack}; // a member: GCC would broadcast a constant anew for every run
    // Coverage reaches at most reach + extension from the centre line's ends, so a segment cut one pixel beyond
    // that outside the clip colours no clipped pixel differently, whatever end it gets at the cut.
    const double margin = profile.reach + profile.extension + 1.0;
    minX_ = clip.x0 - margin, maxX_ = clip.x1 - 1 + margin;
    minY_ = clip.y0 - margin, maxY_ = clip.y1 - 1 + margin;
    segments_.clear();
    for (size_t i = 0; i < lines.size(); ++i)
        addPolyline(lines[i], origin);
    if (segments_.empty())
        return;
    std::sort(segments_.begin(), segments_.end(), [](const Segment &p, const Segment &q) { return p.top < q.top; });
    painter_.reserve(segments_.size());
    active_.resize(std::max(active_.size(), segments_.size() + 1)); // + 1: the idle sentinel emitRow reads
    sweep(sink);
}

void StrokeRasterizer::addPolyline(std::span<const glm::dvec2> points, glm::dvec2 origin)
{
    run_.clear();
    for (const glm::dvec2 &p : points) {
        const glm::dvec2 q = p - origin;
        if (!finite(q)) {
            addRun();
            run_.clear();
        } else if (run_.empty() || !(glm::distance(q, run_.back()) < kSamePoint)) {
            run_.push_back(q);
        }
    }
    addRun();
}

void StrokeRasterizer::addRun()
{
    const size_t n = run_.size();
    if (n < 2)
        return;
    const bool closed = n > 2 && glm::distance(run_.front(), run_.back()) < kSamePoint;
    for (size_t i = 0; i + 1 < n; ++i)
        addSegment(run_[i], run_[i + 1], closed || i > 0, closed || i + 2 < n);
}

void StrokeRasterizer::addSegment(glm::dvec2 a, glm::dvec2 b, bool roundStart, bool roundEnd)
{
    // Liang-Barsky against the expanded clip: a point at 1e12 becomes a point just outside it.
    const glm::dvec2 d = b - a;
    if (!finite(d))
        return;
    const double p[4] = {-d.x, d.x, -d.y, d.y};
    const double q[4] = {a.x - minX_, maxX_ - a.x, a.y - minY_, maxY_ - a.y};
    double t0 = 0.0, t1 = 1.0;
    for (int e = 0; e < 4; ++e) {
        if (p[e] < 0.0)
            t0 = std::max(t0, q[e] / p[e]);
        else if (p[e] > 0.0)
            t1 = std::min(t1, q[e] / p[e]);
        else if (q[e] < 0.0)
            return;
    }
    if (!(t0 < t1))
        return;
    Segment g;
    g.a = t0 > 0.0 ? a + t0 * d : a;
    g.b = t1 < 1.0 ? a + t1 * d : b;
    g.length = glm::distance(g.a, g.b);
    if (!(g.length >= kSamePoint))
        return;
    g.u = (g.b - g.a) / g.length;
    // A cut end lies outside what is drawn: butt is cheaper there.
    g.roundStart = roundStart && t0 <= 0.0;
    g.roundEnd = roundEnd && t1 >= 1.0;
    const double reach = painter_.profile().reach, ext = painter_.profile().extension;
    const Band along = band(g.u.x, g.u.y, g.roundStart ? 0.0 : -ext, g.roundEnd ? g.length : g.length + ext);
    const Band across = band(-g.u.y, g.u.x, -reach, reach);
    g.tLoX = along.loX, g.tHiX = along.hiX, g.tSlope = along.slope;
    g.sLoX = across.loX, g.sHiX = across.hiX, g.sSlope = across.slope;
    g.bodyY0 = std::max(along.y0, across.y0), g.bodyY1 = std::min(along.y1, across.y1);
    g.plain = !g.roundStart && !g.roundEnd && g.bodyY0 == -kInf && g.bodyY1 == kInf;
    g.innerLo = g.roundStart ? 0.0 : ext;
    g.innerHi = g.roundEnd ? g.length : g.length - ext;
    g.dsLanes = float(-g.u.y) + Floats4{};
    g.laneSteps[0] = Floats4{0, 1, 2, 3} * g.dsLanes, g.laneSteps[1] = Floats4{4, 5, 6, 7} * g.dsLanes;
    g.tEnds = Doubles2{g.tLoX, -g.tHiX}, g.tSlopes = Doubles2{g.tSlope, -g.tSlope};
    g.sEnds = Doubles2{g.sLoX, -g.sHiX}, g.sSlopes = Doubles2{g.sSlope, -g.sSlope};
    g.xEnds = Doubles2{g.a.x, -g.a.x};
    g.tsFromY = Doubles2{g.u.y, g.u.x}, g.tsFromX = Doubles2{g.u.x, -g.u.y};
    const double top = std::ceil(std::min(g.a.y, g.b.y) - reach - ext);
    const double bottom = std::floor(std::max(g.a.y, g.b.y) + reach + ext);
    g.top = int(std::max(top, double(clip_.y0)));
    g.bottom = int(std::min(bottom, double(clip_.y1 - 1)));
    g.safeTop = 1, g.safeBottom = 0;
    if (g.plain && std::fabs(g.u.y) >= kSteep) {
        // Rows where the centre line's t is at least kSafeMargin inside [innerLo, innerHi] even at the far side of
        // the band of s (a pixel of the row's run lies within reach + kSlack of the centre line; +1 for good
        // measure): there the band of t contains the band of s, and every pixel of the run lies between the ends.
        const double w = (reach + 1.0) * std::fabs(g.u.x / g.u.y);
        const double tTop = g.innerLo + kSafeMargin + w, tBottom = g.innerHi - kSafeMargin - w;
        if (tTop < tBottom) {
            const double y0 = g.a.y + tTop * g.u.y, y1 = g.a.y + tBottom * g.u.y;
            g.safeTop = std::ceil(std::min(y0, y1)), g.safeBottom = std::floor(std::max(y0, y1));
        }
    }
    if (g.top <= g.bottom)
        segments_.push_back(g);
}

inline bool StrokeRasterizer::rowSpan(const Segment &g, double y, Span &span) const
{
    const double dy = y - g.a.y;
    Doubles2 ends; // {lo, -hi}: the run's ends from a.x before rounding, the high one negated
    const bool safe = y >= g.safeTop && y <= g.safeBottom;
    if (safe) {
        // The band of t contains the band of s by far more than any rounding, so the max below would pick the
        // latter, which is never empty.
        const Doubles2 dys = {dy, dy};
        ends = g.sEnds + g.sSlopes * dys;
    } else if (g.plain) {
        // Both bands at once, lane for lane the scalar expressions below: -(hiX + slope * dy) is
        // -hiX + -slope * dy exactly, and the max of negated values is the negated min.
        const Doubles2 dys = {dy, dy};
        const Doubles2 along = g.tEnds + g.tSlopes * dys, across = g.sEnds + g.sSlopes * dys;
        ends = along < across ? across : along; // std::max lane for lane
        if (!(ends[0] <= -ends[1]))
            return false;
    } else {
        double lo = kInf, hi = -kInf;
        if (dy >= g.bodyY0 && dy <= g.bodyY1) {
            lo = std::max(g.tLoX + g.tSlope * dy, g.sLoX + g.sSlope * dy);
            hi = std::min(g.tHiX + g.tSlope * dy, g.sHiX + g.sSlope * dy);
        }
        // The capsule is convex, so its row is one run: the hull of the body's and the round ends' discs' runs.
        const double reach = painter_.profile().reach;
        const auto disc = [&](glm::dvec2 c) {
            const double cy = y - c.y;
            if (std::fabs(cy) > reach)
                return;
            const double h = std::sqrt(reach * reach - cy * cy);
            lo = std::min(lo, c.x - g.a.x - h), hi = std::max(hi, c.x - g.a.x + h);
        };
        if (g.roundStart)
            disc(g.a);
        if (g.roundEnd)
            disc(g.b);
        if (!(lo <= hi))
            return false;
        ends = Doubles2{lo, -hi};
    }
    // {a.x + lo - kSlack, -(a.x + hi + kSlack)}, clamped first so that the conversions cannot overflow, then ceil of
    // both lanes (floor of x1) by hand: truncate, add one where that went down (no SSE4.1 round on x86-64's base).
    Doubles2 x = (g.xEnds + ends) - slacks_;
    x = x < runMin_ ? runMin_ : x;
    x = runMax_ < x ? runMax_ : x;
    const Ints2 truncated = __builtin_convertvector(x, Ints2);
    const Ints2 ceiling = truncated - __builtin_convertvector(__builtin_convertvector(truncated, Doubles2) < x, Ints2);
    span.x0 = ceiling[0], span.x1 = -ceiling[1];
    if (span.x0 > span.x1)
        return false;
    // For the short kernel's step (emitRow): t at the run's ends and s at x0 as paint() computes them, the
    // rotation's two rows side by side ({t, s} = dy * {u.y, u.x} + dx * {u.x, -u.y}, dx * -u.y being -(dx * u.y)).
    span.fast = false;
    if (!painter_.profile().binary && span.x1 - span.x0 < 8) {
        const double dx = span.x0 - g.a.x;
        if (safe) { // between the ends (the safe rows' margin): s alone
            span.s0 = float(dy * g.u.x - dx * g.u.y);
            span.fast = true;
            return true;
        }
        const Doubles2 ts = dy * g.tsFromY + dx * g.tsFromX;
        const double t = ts[0], tEnd = t + (span.x1 - span.x0) * g.u.x;
        span.fast = !(std::min(t, tEnd) < g.innerLo || std::max(t, tEnd) > g.innerHi);
        span.s0 = float(ts[1]);
    }
    return true;
}

void StrokeRasterizer::sweep(CoverageSink &sink)
{
    const Segment *const segments = segments_.data();
    const size_t segmentCount = segments_.size();
    Span *const spans = active_.data(); // room for every segment and the idle sentinel (rasterize)
    size_t active = 0, next = 0;
    for (int y = segments[0].top; y < clip_.y1; ++y) {
        if (active == 0) {
            if (next == segmentCount)
                break;
            y = std::max(y, segments[next].top);
        }
        while (next < segmentCount && segments[next].top <= y)
            spans[active++] = {kIdle, kIdle, &segments[next++], 0.0f, false};
        // In place: finished segments leave, the others get this row's run (or kIdle) and are inserted in x order
        // (idle ones last), an insertion sort whose order is kept from row to row: the runs come nearly sorted, so
        // it costs about one comparison per run.
        const double row = y;
        size_t kept = 0, runs = 0;
        for (size_t i = 0; i < active; ++i) {
            Span span = spans[i];
            const Segment &g = *span.segment;
            if (g.bottom < y)
                continue;
            if (rowSpan(g, row, span))
                ++runs;
            else
                span.x0 = kIdle;
            size_t k = kept++;
            for (; k > 0 && span.x0 < spans[k - 1].x0; --k)
                spans[k] = spans[k - 1];
            spans[k] = span;
        }
        active = kept;
        spans[active].x0 = kIdle;
        painter_.emitRow(y, spans, runs, sink);
    }
}

} // namespace overlayd
