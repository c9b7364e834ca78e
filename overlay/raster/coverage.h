// SPDX-License-Identifier: Apache-2.0
// Compositing a coverage mask in one colour into the premultiplied overlay layer ("over").
#pragma once

#include <cstddef>
#include <cstdint>

#include "overlay/raster/coverage_sink.h"
#include "overlay/raster/overlay_layer.h"

namespace overlayd {

// A rectangle of whole layer pixels [x0, x1) x [y0, y1).
struct LayerRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    bool empty() const { return x0 >= x1 || y0 >= y1; }
    LayerRect intersect(const LayerRect &other) const;
};

// coverage points at the mask value of layer pixel (rect.x0, rect.y0); rows are coverageStride bytes apart.
// Each pixel of rect becomes colour at opacity alpha * coverage / 255 over what the layer holds, premultiplied and
// rounded so that colour 255 at opacity a stores exactly a.
void compositeCoverage(const uint8_t *coverage, size_t coverageStride, const LayerRect &rect, Rgba colour,
                       OverlayLayer &layer);

// The cached path's sink: each item composited over the layer as it arrives (sink pixels are layer pixels).
class LayerCoverageSink final : public CoverageSink
{
public:
    explicit LayerCoverageSink(OverlayLayer &layer) : layer_(layer) {}

    void begin(Rgba colour) override { colour_ = colour; }
    void row(int y, int x0, const uint8_t *coverage, int count) override
    {
        compositeCoverage(coverage, 0, {x0, y, x0 + count, y + 1}, colour_, layer_);
    }
    void end() override {}

private:
    OverlayLayer &layer_;
    Rgba colour_{};
};

} // namespace overlayd
