// SPDX-License-Identifier: Apache-2.0
// Rasterizer: turns projected primitives into coverage rows for a CoverageSink -- fills as solid rows, strokes
// through StrokeRasterizer, text from TextRenderer's cached glyph coverage.
#pragma once

#include <vector>

#include <glm/vec2.hpp>

#include "overlay/raster/coverage.h"
#include "overlay/raster/coverage_sink.h"
#include "overlay/raster/overlay_layer.h"
#include "overlay/raster/stroke_raster.h"
#include "overlay/raster/text_renderer.h"
#include "overlay/shapes/primitives.h"

namespace overlayd {

// A text plate's padding on each side: 15% of the text size, at least 2 px (3 px at 20 px).
constexpr double kTextPlatePaddingPerPx = 0.15;
constexpr int kMinTextPlatePaddingPx = 2;
int textPlatePadding(double sizePx);

class Rasterizer
{
public:
    explicit Rasterizer(const TextRenderer &text) : text_(text) {}

    // Paints the list item by item (fills, then strokes, then text) through the sink. Primitives are in frame
    // pixels (memory order); the sink's pixel (0, 0) is frame pixel `sinkOrigin`, and nothing is painted outside
    // `sinkClip` (sink pixels: the caller intersects the scissor with the sink's bounds).
    void draw(const DrawList &list, CoverageSink &sink, glm::ivec2 sinkOrigin, const LayerRect &sinkClip);
    // The same over what a layer holds; `clip` is in frame pixels (e.g. the scissor).
    void draw(const DrawList &list, OverlayLayer &layer, glm::ivec2 layerOrigin, const LayerRect &clip);

    // The box a text item occupies, in frame pixels.
    LayerRect textBox(const TextItem &item) const;
    // Its background plate: the box with textPlatePadding(sizePx) more on the left and the right, so that the first
    // and last letters do not touch the plate's edges (the line's height already leaves room above and below).
    LayerRect plateBox(const TextItem &item) const;

private:
    void fill(Rgba colour, const LayerRect &rect, CoverageSink &sink);
    void drawStroke(const StrokeItem &item, CoverageSink &sink, glm::ivec2 origin, const LayerRect &clip);
    void drawText(const TextItem &item, CoverageSink &sink, glm::ivec2 origin, const LayerRect &clip);

    const TextRenderer &text_;
    StrokeRasterizer strokes_;
    Polylines dashed_;           // scratch
    std::vector<uint8_t> solid_; // a row of full coverage, as wide as the widest fill so far
};

} // namespace overlayd
