// SPDX-License-Identifier: Apache-2.0
// The moving-camera blend: coverage rows of a perspective ground grid (~8% of the pixels, many short runs per row)
// blended straight into cold frames by FrameCoverageSink, against a cold memcpy of the same frame in the same run.
// `cached` is today's dynamic path fed the same rows: composite into an RGBA layer, convert it, blend it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "cold_frames.h"
#include "overlay/blend/frame_coverage_sink.h"
#include "overlay/blend/native_layer.h"
#include "overlay/raster/coverage.h"

namespace overlayd {
namespace {

using bench::memcpyBench;
using bench::Ring;

constexpr double kCoverage = 0.08;

struct Row {
    int y, x0, count;
    size_t offset; // into Rows::coverage
};

struct Item {
    Rgba colour;
    size_t begin, end; // rows
};

struct Rows {
    std::vector<Row> rows;
    std::vector<Item> items;
    std::vector<uint8_t> coverage;
    size_t covered = 0;
};

// One anti-aliased line 2 px wide through a and b, clipped to the frame: per row, the pixels whose centre lies
// within 1.5 px of the line (perpendicular distance), coverage falling off linearly over the last pixel.
void addLine(Rows &out, double ax, double ay, double bx, double by, Rgba colour, int width, int height)
{
    const double dx = bx - ax, dy = by - ay, length = std::hypot(dx, dy);
    const double nx = -dy / length, ny = dx / length, c = nx * ax + ny * ay, reach = 1.5;
    Item item{colour, out.rows.size(), 0};
    for (int y = 0; y < height; ++y) {
        // |nx x + ny y - c| <= reach, solved for x (lines here are never exactly horizontal or vertical).
        const double x0 = (c - ny * y - reach) / nx, x1 = (c - ny * y + reach) / nx;
        const int lo = std::max(0, int(std::ceil(std::min(x0, x1)))), hi = std::min(width - 1, int(std::max(x0, x1)));
        if (lo > hi)
            continue;
        const size_t offset = out.coverage.size();
        for (int x = lo; x <= hi; ++x) {
            const double distance = std::abs(nx * x + ny * y - c);
            out.coverage.push_back(uint8_t(std::lround(255 * std::clamp(reach - distance, 0.0, 1.0))));
        }
        out.rows.push_back({y, lo, hi - lo + 1, offset});
        out.covered += size_t(hi - lo + 1);
    }
    item.end = out.rows.size();
    out.items.push_back(item);
}

// Lines converging on a vanishing point above the frame and rungs that crowd towards the horizon, added in turn
// until kCoverage of the pixels are reached (overlaps counted twice: an estimate, printed as a counter).
Rows perspectiveGrid(int width, int height)
{
    Rows out;
    const Rgba colours[] = {{230, 230, 230, 255}, {255, 60, 0, 255}, {40, 80, 255, 200}};
    const double vx = width * 0.5, vy = -0.6 * height;
    for (int k = 0; out.covered < kCoverage * width * height; ++k) {
        const double t = (k / 2) * 0.618034 - std::floor((k / 2) * 0.618034);
        if (k % 2 == 0) {
            addLine(out, vx + 0.01, vy, -width + 3.0 * width * t, height + 0.3, colours[k % 3], width, height);
        } else {
            const double y = vy + (height - vy) * std::sqrt(t);
            addLine(out, -1.0, y, width + 1.0, y + 0.04 * height, colours[k % 3], width, height);
        }
    }
    return out;
}

void paint(const Rows &grid, CoverageSink &sink)
{
    for (const Item &item : grid.items) {
        sink.begin(item.colour);
        for (size_t r = item.begin; r < item.end; ++r) {
            const Row &row = grid.rows[r];
            sink.row(row.y, row.x0, grid.coverage.data() + row.offset, row.count);
        }
        sink.end();
    }
}

// The cached path's way of taking rows: each composited over the RGBA layer as it arrives.
class LayerSink final : public CoverageSink
{
public:
    explicit LayerSink(OverlayLayer &layer) : layer_(layer) {}
    void begin(Rgba colour) override { colour_ = colour; }
    void row(int y, int x0, const uint8_t *coverage, int count) override
    {
        compositeCoverage(coverage, size_t(count), {x0, y, x0 + count, y + 1}, colour_, layer_);
    }
    void end() override {}

private:
    OverlayLayer &layer_;
    Rgba colour_{};
};

void counters(benchmark::State &state, const Rows &grid, int width, int height)
{
    state.counters["coverage_%"] = 100.0 * grid.covered / (double(width) * height);
    state.counters["items"] = double(grid.items.size());
    state.counters["row_calls"] = double(grid.rows.size());
}

void sinkBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    const Rows grid = perspectiveGrid(int(width), int(height));
    FrameCoverageSink sink(format, Colorimetry{});
    Ring ring(format, width, height);
    size_t i = 0;
    for (auto _ : state) {
        sink.setFrame(ring.layout.view(ring.frame(i++)));
        paint(grid, sink);
        benchmark::ClobberMemory();
    }
    counters(state, grid, int(width), int(height));
}

// The same rows through the cached path, as a moving camera pays for it today: clear, composite, convert, blend.
void cachedBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    const Rows grid = perspectiveGrid(int(width), int(height));
    OverlayLayer layer(width, height);
    LayerSink layerSink(layer);
    paint(grid, layerSink);
    layer.updateSpans();
    auto native = NativeLayer::convert(layer, format, Colorimetry{});
    Ring ring(format, width, height);
    size_t i = 0;
    for (auto _ : state) {
        layer.clearCovered();
        paint(grid, layerSink);
        layer.updateSpans();
        const Status converted = native->update(layer, Colorimetry{});
        const Status blended = native->blend(ring.layout.view(ring.frame(i++)));
        benchmark::DoNotOptimize(converted.ok() && blended.ok());
    }
    counters(state, grid, int(width), int(height));
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    constexpr const char *kFamily = "BM_CoverageSink";
    for (const bench::FrameCase &c : bench::kFrameCases) {
        bench::registerCase(kFamily, "sink", sinkBench, c);
        bench::registerCase(kFamily, "cached", cachedBench, c);
        bench::registerCase(kFamily, bench::kMemcpyCold, memcpyBench, c);
    }
    bench::printRatiosToMemcpy(*bench::runAll(), kFamily, {"sink", "cached"});
    return 0;
}
