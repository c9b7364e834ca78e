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
// which take a scalar formula). Cost: covered pixels plus rows spanned, whatever the bounding box; no allocation
// once the scratch has grown. Known limit: where two different segments each cover part of a pixel (a crossing's
// or a sharp joint's inner corner) the max is below the union's area.
#include "overlay/stroke_raster.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

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

// The trimming of a run's zero ends, 8 bytes at a time: a byte loop's exit branch is mispredicted about once a run.
// Reads up to 7 bytes past p + n (the scratch's slack), never before p.

uint64_t word(const uint8_t *p, int valid)
{
    uint64_t w;
    __builtin_memcpy(&w, p, sizeof w);
    return valid >= 8 ? w : w & ((uint64_t(1) << (8 * valid)) - 1);
}

// The first non-zero byte of p[0, n), or n.
int firstNonZero(const uint8_t *p, int n)
{
    for (int i = 0; i < n; i += 8)
        if (const uint64_t w = word(p + i, n - i))
            return i + std::countr_zero(w) / 8;
    return n;
}

// One past the last non-zero byte of p[0, n) (p[0, n) has one).
int endNonZero(const uint8_t *p, int n)
{
    for (int e = n; e > 0; e -= 8) {
        const uint64_t w = e >= 8 ? word(p + e - 8, 8) : word(p, e) << (8 * (8 - e));
        if (w)
            return e - std::countl_zero(w) / 8;
    }
    return 0;
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
    clip_ = clip;
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
    const double top = std::ceil(std::min(g.a.y, g.b.y) - reach - ext);
    const double bottom = std::floor(std::max(g.a.y, g.b.y) + reach + ext);
    g.top = int(std::max(top, double(clip_.y0)));
    g.bottom = int(std::min(bottom, double(clip_.y1 - 1)));
    if (g.top <= g.bottom)
        segments_.push_back(g);
}

void StrokeRasterizer::sweep(CoverageSink &sink)
{
    active_.clear();
    size_t next = 0;
    for (int y = segments_.front().top; y < clip_.y1; ++y) {
        if (active_.empty()) {
            if (next == segments_.size())
                break;
            y = std::max(y, segments_[next].top);
        }
        while (next < segments_.size() && segments_[next].top <= y)
            active_.push_back(uint32_t(next++));
        spans_.clear();
        idle_.clear();
        for (const uint32_t i : active_) {
            Span span{0, 0, i};
            if (segments_[i].bottom < y)
                continue;
            if (rowSpan(segments_[i], y, span))
                spans_.push_back(span);
            else
                idle_.push_back(i);
        }
        // Sorted by x, and the active list kept in that order: the next row's runs come nearly sorted, so the
        // insertion sort costs about one comparison per run.
        for (size_t j = 1; j < spans_.size(); ++j)
            for (size_t k = j; k > 0 && spans_[k].x0 < spans_[k - 1].x0; --k)
                std::swap(spans_[k], spans_[k - 1]);
        active_.clear();
        for (const Span &span : spans_)
            active_.push_back(span.segment);
        active_.insert(active_.end(), idle_.begin(), idle_.end());
        emitRow(y, sink);
    }
}

bool StrokeRasterizer::rowSpan(const Segment &g, int y, Span &span) const
{
    const double dy = y - g.a.y, reach = profile_.reach;
    double lo = kInf, hi = -kInf;
    if (dy >= g.bodyY0 && dy <= g.bodyY1) {
        lo = std::max(g.tLoX + g.tSlope * dy, g.sLoX + g.sSlope * dy);
        hi = std::min(g.tHiX + g.tSlope * dy, g.sHiX + g.sSlope * dy);
    }
    // The capsule is convex, so its row is one run: the hull of the body's and the round ends' discs' runs.
    for (int end = g.roundStart ? 0 : 1; end < (g.roundEnd ? 2 : 1); ++end) {
        const glm::dvec2 c = end == 0 ? g.a : g.b;
        const double cy = y - c.y;
        if (std::fabs(cy) > reach)
            continue;
        const double h = std::sqrt(reach * reach - cy * cy);
        lo = std::min(lo, c.x - g.a.x - h), hi = std::max(hi, c.x - g.a.x + h);
    }
    if (!(lo <= hi))
        return false;
    // Clamped first, so that the conversions cannot overflow; ceil and floor by hand (without SSE4.1 the library's
    // take about 20 instructions each, the largest cost of this function).
    const double x0 = std::clamp(g.a.x + lo - kSlack, double(clip_.x0), double(clip_.x1));
    const double x1 = std::clamp(g.a.x + hi + kSlack, clip_.x0 - 1.0, clip_.x1 - 1.0);
    span.x0 = int(x0) + (double(int(x0)) < x0);
    span.x1 = int(x1) - (double(int(x1)) > x1);
    return span.x0 <= span.x1;
}

void StrokeRasterizer::emitRow(int y, CoverageSink &sink)
{
    for (size_t i = 0; i < spans_.size();) {
        // Overlapping or touching runs share one scratch run (max per pixel) and one row() call.
        const int x0 = spans_[i].x0;
        int x1 = spans_[i].x1;
        size_t j = i + 1;
        for (; j < spans_.size() && spans_[j].x0 <= x1 + 1; ++j)
            x1 = std::max(x1, spans_[j].x1);
        uint8_t *row = row_.data() + (x0 - clip_.x0);
        const bool alone = j == i + 1;
        if (!alone)
            std::fill(row, row + (x1 - x0 + 1), uint8_t(0));
        for (; i < j; ++i)
            paint(segments_[spans_[i].segment], y, spans_[i].x0, spans_[i].x1 - spans_[i].x0 + 1,
                  row + (spans_[i].x0 - x0), alone);
        const int n = x1 - x0 + 1;
        if (row[0] != 0 && row[n - 1] != 0) { // the usual case: a run's end pixels are covered
            sink.row(y, x0, row, n);
            continue;
        }
        const int first = firstNonZero(row, n);
        if (first < n)
            sink.row(y, x0 + first, row + first, endNonZero(row, n) - first);
    }
}

} // namespace overlayd
