// SPDX-License-Identifier: Apache-2.0
// Items become coverage rows: fills are solid rows, strokes are dashed first and then rasterized analytically
// (StrokeRasterizer: a full-frame OpenCV mask cost more than a whole frame copy per redraw), text rows come from
// the glyphs TextRenderer caches.
#include "overlay/raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "overlay/raster/dash.h"

namespace overlayd {

namespace {

LayerRect shifted(const LayerRect &r, glm::ivec2 by)
{
    return {r.x0 - by.x, r.y0 - by.y, r.x1 - by.x, r.y1 - by.y};
}

// Calls paint(start, count, coverage) for each stretch of a text row that has ink: a text's box is mostly empty
// (between the glyphs, above and below them), and a sink blends every pixel it is given, zero or not. Runs are split
// where kGap pixels in a row have none (fewer are blended through: a call costs more than a few pixels).
template<typename Paint>
void inkRuns(const uint8_t *row, int width, Paint &&paint)
{
    constexpr int kGap = 4;
    for (int x = 0; x < width;) {
        uint64_t word = 0;
        while (x + 8 <= width && (std::memcpy(&word, row + x, 8), word == 0)) // empty stretches, 8 pixels a step
            x += 8;
        while (x < width && row[x] == 0)
            ++x;
        const int start = x;
        int end = x, zeros = 0;
        for (; x < width && zeros < kGap; ++x) {
            if (row[x] != 0)
                end = x + 1, zeros = 0;
            else
                ++zeros;
        }
        if (end > start)
            paint(start, end - start, row + start);
    }
}

} // namespace

void Rasterizer::draw(const DrawList &list, OverlayLayer &layer, glm::ivec2 layerOrigin, const LayerRect &clip)
{
    LayerCoverageSink sink(layer);
    draw(list, sink, layerOrigin,
         shifted(clip, layerOrigin).intersect({0, 0, int(layer.width()), int(layer.height())}));
}

void Rasterizer::draw(const DrawList &list, CoverageSink &sink, glm::ivec2 sinkOrigin, const LayerRect &sinkClip)
{
    if (sinkClip.empty())
        return;
    for (const FillItem &item : list.fills)
        fill(item.colour, shifted({item.x0, item.y0, item.x1, item.y1}, sinkOrigin).intersect(sinkClip), sink);
    for (const StrokeItem &stroke : list.strokes)
        drawStroke(stroke, sink, sinkOrigin, sinkClip);
    for (const TextItem &text : list.texts)
        drawText(text, sink, sinkOrigin, sinkClip);
}

void Rasterizer::fill(Rgba colour, const LayerRect &rect, CoverageSink &sink)
{
    if (rect.empty())
        return;
    const int width = rect.x1 - rect.x0;
    if (solid_.size() < size_t(width))
        solid_.assign(size_t(width), 255);
    sink.begin(colour);
    for (int y = rect.y0; y < rect.y1; ++y)
        sink.row(y, rect.x0, solid_.data(), width);
    sink.end();
}

void Rasterizer::drawStroke(const StrokeItem &item, CoverageSink &sink, glm::ivec2 origin, const LayerRect &clip)
{
    if (item.lines.points.empty() || !(item.style.width > 0.0) || item.style.colour.a == 0)
        return;
    const Polylines *lines = &item.lines;
    if (!item.style.dash.empty()) {
        dashed_.clear();
        applyDash(item.lines, item.style.dash, dashed_);
        lines = &dashed_;
    }
    if (lines->points.empty())
        return;
    sink.begin(item.style.colour);
    strokes_.rasterize(*lines, item.style.width, item.style.antialias, glm::dvec2(origin), clip, sink);
    sink.end();
}

LayerRect Rasterizer::textBox(const TextItem &item) const
{
    const TextRenderer::Box box = text_.measure(item.text, item.sizePx, item.antialias);
    // Right: the box's last column on the anchor; Centre: its middle column (the left one of two).
    const int shift = item.align == TextAlign::Right    ? box.width - 1
                      : item.align == TextAlign::Centre ? (box.width - 1) / 2
                                                        : 0;
    const int x = int(std::lround(item.anchor.x)) - shift;
    const int y = int(std::lround(item.anchor.y)) - (item.anchorAtBottom ? box.height() - 1 : 0);
    return {x, y, x + box.width, y + box.height()};
}

int textPlatePadding(double sizePx)
{
    return std::max(kMinTextPlatePaddingPx, int(std::lround(kTextPlatePaddingPerPx * sizePx)));
}

LayerRect Rasterizer::plateBox(const TextItem &item) const
{
    LayerRect box = textBox(item);
    const int padding = textPlatePadding(item.sizePx);
    box.x0 -= padding;
    box.x1 += padding;
    return box;
}

void Rasterizer::drawText(const TextItem &item, CoverageSink &sink, glm::ivec2 origin, const LayerRect &clip)
{
    if (item.text.empty() || !std::isfinite(item.anchor.x) || !std::isfinite(item.anchor.y))
        return;
    const LayerRect box = shifted(textBox(item), origin);
    if (item.background)
        fill(*item.background, shifted(plateBox(item), origin).intersect(clip), sink);
    const cv::Mat coverage = text_.render(item.text, item.sizePx, item.antialias);
    const LayerRect r = box.intersect(clip).intersect({box.x0, box.y0, box.x0 + coverage.cols, box.y0 + coverage.rows});
    if (r.empty())
        return;
    sink.begin(item.colour);
    for (int y = r.y0; y < r.y1; ++y)
        inkRuns(coverage.ptr(y - box.y0, r.x0 - box.x0), r.x1 - r.x0,
                [&](int start, int count, const uint8_t *run) { sink.row(y, r.x0 + start, run, count); });
    sink.end();
}

} // namespace overlayd
