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
// in one pass), and a run that touches no other and lies between its segment's ends is written by one inlined step
// of the short kernel. Every shortcut evaluates the same expressions as the general path, so the bytes are the same.
// Cost: covered pixels plus rows spanned, whatever the bounding box; no allocation once the scratch has grown.
// Known limit: where two different segments each cover part of a pixel (a crossing's or a sharp joint's inner
// corner) the max is below the union's area.
#include "overlay/stroke_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFlat = 1e-9;      // a direction component this small is 0 (never divided by)
constexpr double kSamePoint = 1e-9; // consecutive points closer than this (px) are one point
constexpr double kSlack = 1e-7;
constexpr double kMaxWidth = 1e6; // pixel runs widen by this so a centre exactly on a binary edge is evaluated

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
    // Wider than any frame is as wide as one: 255 * reach must stay far from the int range of the kernels.
    const double hw = 0.5 * std::min(width, kMaxWidth);
    if (!antialias)
        profile_ = {255.0f, 255.0f, std::max(hw, 0.5), 0.0, true};
    else if (width < 1.0)
        profile_ = {float(255.0 * width), float(255.0 * width), 1.0, 0.5, false};
    else
        profile_ = {255.0f, 255.0f, hw + 0.5, 0.5, false};
    profile_.gainLanes = profile_.gain + Floats4{};
    profile_.reachLanes = float(profile_.reach) + Floats4{};
    profile_.peakLanes = float(int(profile_.peak + 0.5f)) + Floats4{};
    clip_ = clip;
    runX0Min_ = clip.x0, runX0Max_ = clip.x1;
    runX1Min_ = clip.x0 - 1.0, runX1Max_ = clip.x1 - 1.0;
    // Coverage reaches at most reach + extension from the centre line's ends, so a segment cut one pixel beyond
    // that outside the clip colours no clipped pixel differently, whatever end it gets at the cut.
    const double margin = profile_.reach + profile_.extension + 1.0;
    minX_ = clip.x0 - margin, maxX_ = clip.x1 - 1 + margin;
    minY_ = clip.y0 - margin, maxY_ = clip.y1 - 1 + margin;
    segments_.clear();
    for (size_t i = 0; i < lines.size(); ++i)
        addPolyline(lines[i], origin);
    if (segments_.empty())
        return;
    std::sort(segments_.begin(), segments_.end(), [](const Segment &p, const Segment &q) { return p.top < q.top; });
    row_.resize(std::max(row_.size(), size_t(int64_t(clip.x1) - clip.x0 + kStrokeRowSlack)));
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
    const double reach = profile_.reach, ext = profile_.extension;
    const Band along = band(g.u.x, g.u.y, g.roundStart ? 0.0 : -ext, g.roundEnd ? g.length : g.length + ext);
    const Band across = band(-g.u.y, g.u.x, -reach, reach);
    g.tLoX = along.loX, g.tHiX = along.hiX, g.tSlope = along.slope;
    g.sLoX = across.loX, g.sHiX = across.hiX, g.sSlope = across.slope;
    g.bodyY0 = std::max(along.y0, across.y0), g.bodyY1 = std::min(along.y1, across.y1);
    g.plain = !g.roundStart && !g.roundEnd && g.bodyY0 == -kInf && g.bodyY1 == kInf;
    g.innerLo = g.roundStart ? 0.0 : ext;
    g.innerHi = g.roundEnd ? g.length : g.length - ext;
    g.dsLanes = float(-g.u.y) + Floats4{};
    const double top = std::ceil(std::min(g.a.y, g.b.y) - reach - ext);
    const double bottom = std::floor(std::max(g.a.y, g.b.y) + reach + ext);
    g.top = int(std::max(top, double(clip_.y0)));
    g.bottom = int(std::min(bottom, double(clip_.y1 - 1)));
    if (g.top <= g.bottom)
        segments_.push_back(g);
}

inline bool StrokeRasterizer::rowSpan(const Segment &g, int y, Span &span) const
{
    const double dy = y - g.a.y, reach = profile_.reach;
    double lo = kInf, hi = -kInf;
    if (g.plain || (dy >= g.bodyY0 && dy <= g.bodyY1)) { // a plain segment's body rows are all rows (finite dy)
        lo = std::max(g.tLoX + g.tSlope * dy, g.sLoX + g.sSlope * dy);
        hi = std::min(g.tHiX + g.tSlope * dy, g.sHiX + g.sSlope * dy);
    }
    // The capsule is convex, so its row is one run: the hull of the body's and the round ends' discs' runs.
    const auto disc = [&](glm::dvec2 c) {
        const double cy = y - c.y;
        if (std::fabs(cy) > reach)
            return;
        const double h = std::sqrt(reach * reach - cy * cy);
        lo = std::min(lo, c.x - g.a.x - h), hi = std::max(hi, c.x - g.a.x + h);
    };
    if (!g.plain) {
        if (g.roundStart)
            disc(g.a);
        if (g.roundEnd)
            disc(g.b);
    }
    if (!(lo <= hi))
        return false;
    // Clamped first, so that the conversions cannot overflow; ceil and floor by hand (without SSE4.1 the library's
    // take about 20 instructions each, the largest cost of this function).
    const double x0 = std::clamp(g.a.x + lo - kSlack, runX0Min_, runX0Max_);
    const double x1 = std::clamp(g.a.x + hi + kSlack, runX1Min_, runX1Max_);
    span.x0 = int(x0) + (double(int(x0)) < x0);
    span.x1 = int(x1) - (double(int(x1)) > x1);
    return span.x0 <= span.x1;
}

void StrokeRasterizer::sweep(CoverageSink &sink)
{
    active_.clear();
    const Segment *const segments = segments_.data();
    const size_t segmentCount = segments_.size();
    size_t next = 0;
    for (int y = segments[0].top; y < clip_.y1; ++y) {
        if (active_.empty()) {
            if (next == segmentCount)
                break;
            y = std::max(y, segments[next].top);
        }
        while (next < segmentCount && segments[next].top <= y)
            active_.push_back({kIdle, kIdle, &segments[next++]});
        // In place: finished segments leave, the others get this row's run (or kIdle) and are inserted in x order
        // (idle ones last), an insertion sort whose order is kept from row to row: the runs come nearly sorted, so
        // it costs about one comparison per run.
        Span *const spans = active_.data();
        const size_t active = active_.size();
        size_t kept = 0, runs = 0;
        for (size_t i = 0; i < active; ++i) {
            Span span = spans[i];
            const Segment &g = *span.segment;
            if (g.bottom < y)
                continue;
            if (rowSpan(g, y, span))
                ++runs;
            else
                span.x0 = kIdle;
            size_t k = kept++;
            for (; k > 0 && span.x0 < spans[k - 1].x0; --k)
                spans[k] = spans[k - 1];
            spans[k] = span;
        }
        active_.resize(kept);
        emitRow(y, spans, runs, sink);
    }
}

} // namespace overlayd
