// SPDX-License-Identifier: Apache-2.0
// CoverageSink: where rasterized coverage goes, row by row -- an RGBA layer (cached overlays) or straight into a
// frame in its own pixel format (a moving camera, where a cached layer would be redrawn every frame anyway).
#pragma once

#include <cstddef>
#include <cstdint>

#include "overlay/raster/overlay_layer.h"

namespace overlayd {

// How far past a rowRuns() run's last pixel its coverage array may be read (not used): a sink may load whole
// vectors of a short run straight from the producer's row.
inline constexpr int kCoverageReadAhead = 16;

// One run of a row: pixels [x0, x0 + count) take coverage[0 .. count).
struct CoverageRun {
    int x0, count;
    const uint8_t *coverage;
};

// One item (a stroke, a fill, a text) is painted as begin(colour), then row() calls, then end(). Within an item:
// rows come in increasing y; several row() calls for one y come in increasing x with at least one pixel between
// them (touching runs are one run), so that no 4:2:2 macropixel is split between two calls; coverage is 0..255
// per pixel (0 is allowed and changes nothing). Coordinates are the sink's own pixels (a layer's or a
// frame's), already clipped to it by the rasterizer. Items are painted "over" each other in call order.
class CoverageSink
{
public:
    virtual ~CoverageSink() = default;

    // colour is straight (not premultiplied); the item's opacity at a pixel is colour.a * coverage / 255.
    virtual void begin(Rgba colour) = 0;
    // Pixels [x0, x0 + count) of row y take coverage[0 .. count).
    virtual void row(int y, int x0, const uint8_t *coverage, int count) = 0;
    // All of an item's runs in row y at once (in increasing x, a pixel apart at least): the same as row() for
    // each in turn, but a sink may hoist its per-row work out of the loop. Unlike row()'s, each run's coverage
    // can be read kCoverageReadAhead bytes past its last pixel (whatever those bytes hold).
    virtual void rowRuns(int y, const CoverageRun *runs, size_t count)
    {
        for (size_t i = 0; i < count; ++i)
            row(y, runs[i].x0, runs[i].coverage, runs[i].count);
    }
    // The item is complete: a sink that groups rows (chroma shared by two rows) flushes here.
    virtual void end() = 0;
};

} // namespace overlayd
