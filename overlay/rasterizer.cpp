// Strokes become filled anti-aliased quads in a coverage mask (OpenCV's cv::line only takes whole-pixel widths),
// which is then composited in the stroke's colour; text comes from TextRenderer.
//
// OpenCV's anti-aliased polygon fill paints a ~1 px wide anti-aliased line along every edge on top of the
// interior, so a polygon covers about 1.35 px more than its area across (measured: a 2 px cv::line covers 3.5 px).
// Quads are therefore inset by kAaInset on each side, which brings the coverage across a stroke within about
// 0.3 px of the requested width for widths >= 1.4 px. Thinner strokes are 1 px anti-aliased lines (about 1.4 px of
// coverage) whose opacity is scaled by width / 1.4, so a thin line keeps its total ink.
#include "overlay/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>

#include "overlay/dash.h"

namespace overlayd {

namespace {

constexpr int kShift = 8; // sub-pixel bits of OpenCV's fixed-point coordinates
constexpr double kOne = 1 << kShift;
constexpr double kAaInset = 0.675;
constexpr double kThinCoverage = 1.4;  // coverage across a 1 px cv::line LINE_AA
constexpr double kSharpTurnCos = 0.94; // joints turning more than ~20 degrees get a round join

cv::Point fixedPoint(const glm::dvec2 &p)
{
    return {int(std::lround(p.x * kOne)), int(std::lround(p.y * kOne))};
}

bool before(const cv::Point &a, const cv::Point &b)
{
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

// OpenCV's anti-aliased edges depend on the direction they are walked in; drawing every line and quad in one
// canonical order makes a polyline and its reverse (and both viewport origins) produce the same pixels.
void canonicalLine(cv::Point &a, cv::Point &b)
{
    if (before(b, a))
        std::swap(a, b);
}

void canonicalQuad(cv::Point (&quad)[4])
{
    const cv::Point e1 = quad[1] - quad[0], e2 = quad[2] - quad[0];
    if (double(e1.x) * e2.y - double(e1.y) * e2.x < 0)
        std::swap(quad[1], quad[3]);
    const int first = int(std::min_element(quad, quad + 4, before) - quad);
    std::rotate(quad, quad + first, quad + 4);
}

LayerRect bounds(const Polylines &lines, double margin)
{
    // Clamped so that a wild screen coordinate cannot overflow an int; the result is clipped to the layer anyway.
    constexpr double kLimit = 1e7;
    glm::dvec2 low(kLimit), high(-kLimit);
    for (const glm::dvec2 &p : lines.points)
        low = glm::min(low, p), high = glm::max(high, p);
    low = glm::max(low, glm::dvec2(-kLimit)), high = glm::min(high, glm::dvec2(kLimit));
    return {int(std::floor(low.x - margin)), int(std::floor(low.y - margin)), int(std::ceil(high.x + margin)) + 1,
            int(std::ceil(high.y + margin)) + 1};
}

LayerRect shifted(const LayerRect &r, glm::ivec2 by)
{
    return {r.x0 - by.x, r.y0 - by.y, r.x1 - by.x, r.y1 - by.y};
}

} // namespace

void Rasterizer::draw(const DrawList &list, OverlayLayer &layer, glm::ivec2 layerOrigin, const LayerRect &clip)
{
    if (mask_.rows < int(layer.height()) || mask_.cols < int(layer.width()))
        mask_ = cv::Mat::zeros(std::max(mask_.rows, int(layer.height())), std::max(mask_.cols, int(layer.width())),
                               CV_8UC1);
    const LayerRect layerClip = shifted(clip, layerOrigin).intersect({0, 0, int(layer.width()), int(layer.height())});
    if (layerClip.empty())
        return;
    for (const FillItem &fill : list.fills) {
        const LayerRect r = shifted({fill.x0, fill.y0, fill.x1, fill.y1}, layerOrigin).intersect(layerClip);
        const std::vector<uint8_t> full(std::max(r.x1 - r.x0, 0), 255);
        compositeCoverage(full.data(), 0, r, fill.colour, layer);
    }
    for (const StrokeItem &stroke : list.strokes)
        drawStroke(stroke, layer, layerOrigin, layerClip);
    for (const TextItem &text : list.texts)
        drawText(text, layer, layerOrigin, layerClip);
}

void Rasterizer::strokePolyline(std::span<const glm::dvec2> line, glm::dvec2 shift, const StrokeStyle &style,
                                cv::Mat &target, const cv::Scalar &colour)
{
    const int lineType = style.antialias ? cv::LINE_AA : cv::LINE_8;
    const bool thin = style.width < kThinCoverage;
    const double half = std::max(0.5 * style.width - (style.antialias ? kAaInset : 0.0), 0.0);
    for (size_t i = 1; i < line.size(); ++i) {
        const glm::dvec2 a = line[i - 1] - shift, b = line[i] - shift;
        if (thin) {
            cv::Point p = fixedPoint(a), q = fixedPoint(b);
            canonicalLine(p, q);
            cv::line(target, p, q, colour, 1, lineType, kShift);
            continue;
        }
        const double length = glm::distance(a, b);
        if (length == 0.0)
            continue;
        const glm::dvec2 d = (b - a) / length, n(-d.y, d.x);
        // Interior joints overlap by a pixel so that the anti-aliased ends of two quads never leave a seam.
        const double overlap = std::max(half, 1.0);
        const double extendA = i > 1 ? overlap : 0.0, extendB = i + 1 < line.size() ? overlap : 0.0;
        const glm::dvec2 a0 = a - extendA * d, b0 = b + extendB * d;
        cv::Point quad[4] = {fixedPoint(a0 + half * n), fixedPoint(b0 + half * n), fixedPoint(b0 - half * n),
                             fixedPoint(a0 - half * n)};
        canonicalQuad(quad);
        cv::fillConvexPoly(target, quad, 4, colour, lineType, kShift);
        if (i + 1 < line.size() && half >= 1.0 && glm::dot(d, glm::normalize(line[i + 1] - line[i])) < kSharpTurnCos)
            cv::circle(target, fixedPoint(b), int(std::lround(half * kOne)), colour, -1, lineType, kShift);
    }
}

// An opaque colour is drawn straight onto the layer: OpenCV's anti-aliased blend, dst += (colour - dst) * a on all
// four channels, is exactly the premultiplied "over" of an opaque colour (alpha += (255 - alpha) * a), and it
// touches only the drawn pixels. A translucent colour needs its coverage first (two overlapping edges of one stroke
// must not darken twice), so it goes through the mask.
void Rasterizer::drawStroke(const StrokeItem &item, OverlayLayer &layer, glm::ivec2 origin, const LayerRect &clip)
{
    if (item.lines.points.empty() || item.style.width <= 0.0 || clip.empty())
        return;
    const Polylines *lines = &item.lines;
    if (!item.style.dash.empty()) {
        dashed_.clear();
        applyDash(item.lines, item.style.dash, dashed_);
        lines = &dashed_;
    }
    if (lines->points.empty())
        return;
    Rgba colour = item.style.colour;
    if (item.style.width < kThinCoverage)
        colour.a = uint8_t(std::lround(colour.a * std::min(1.0, item.style.width / kThinCoverage)));
    const cv::Rect clipRect(clip.x0, clip.y0, clip.x1 - clip.x0, clip.y1 - clip.y0);
    const glm::dvec2 shift = glm::dvec2(origin) + glm::dvec2(clip.x0, clip.y0);
    if (colour.a == 255) {
        cv::Mat target = cv::Mat(int(layer.height()), int(layer.width()), CV_8UC4, layer.data())(clipRect);
        for (size_t i = 0; i < lines->size(); ++i)
            strokePolyline((*lines)[i], shift, item.style, target, cv::Scalar(colour.r, colour.g, colour.b, 255));
        return;
    }
    cv::Mat target = mask_(clipRect);
    for (size_t i = 0; i < lines->size(); ++i)
        strokePolyline((*lines)[i], shift, item.style, target, cv::Scalar(255));
    const LayerRect r = shifted(bounds(*lines, 0.5 * item.style.width + 2.0), origin).intersect(clip);
    if (r.empty())
        return;
    compositeCoverage(mask_.ptr(r.y0, r.x0), mask_.step, r, colour, layer);
    mask_(cv::Rect(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0)).setTo(0);
}

LayerRect Rasterizer::textBox(const TextItem &item) const
{
    const TextRenderer::Box box = text_.measure(item.text, item.sizePx);
    const int x = int(std::lround(item.anchor.x));
    const int y = int(std::lround(item.anchor.y)) - (item.anchorAtBottom ? box.height() - 1 : 0);
    return {x, y, x + box.width, y + box.height()};
}

void Rasterizer::drawText(const TextItem &item, OverlayLayer &layer, glm::ivec2 origin, const LayerRect &clip)
{
    if (item.text.empty())
        return;
    const LayerRect box = shifted(textBox(item), origin);
    if (item.background) {
        const LayerRect r = box.intersect(clip);
        const std::vector<uint8_t> full(std::max(r.x1 - r.x0, 0), 255);
        compositeCoverage(full.data(), 0, r, *item.background, layer);
    }
    const cv::Mat coverage = text_.render(item.text, item.sizePx, item.antialias);
    const LayerRect r = box.intersect(clip).intersect({box.x0, box.y0, box.x0 + coverage.cols, box.y0 + coverage.rows});
    if (!r.empty())
        compositeCoverage(coverage.ptr(r.y0 - box.y0, r.x0 - box.x0), coverage.step, r, item.colour, layer);
}

} // namespace overlayd
