// SPDX-License-Identifier: Apache-2.0
// A privacy mask against an opaque overlay of the same area, in the same run (BM_Mask/<kind>/<format>/<size>):
//   opaque_overlay  the cached overlay path: a NativeLayer of the polygon drawn opaque (OpenCV fillPoly) blended
//   fill            the mask filled with a colour (MaskPainter::fill over the polygon's macropixel spans)
//   pixelate<N>     the mask pixelated in N px blocks (8, 16, 32)
//   memcpy_cold     the usual yardstick
// In every format family the painter has a path for (packed 4:2:2, semi-planar and planar 4:2:0, 3- and 4-byte RGB,
// grey), at 720p and 1080p. The polygon is a concave hexagon over about a third of the frame; frames come from a
// ring larger than the caches.
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cold_frames.h"
#include "overlay/blend/mask_painter.h"
#include "overlay/blend/native_layer.h"
#include "overlay/raster/polygon_spans.h"

namespace overlayd {
namespace {

using bench::memcpyBench;
using bench::Ring;

constexpr const char *kFamily = "BM_Mask";

std::vector<cv::Point> outline(unsigned width, unsigned height)
{
    const int w = int(width), h = int(height);
    return {{w / 10, h / 10},    {w * 6 / 10, h / 8},      {w * 7 / 10, h / 2},
            {w / 2, h * 4 / 10}, {w * 6 / 10, h * 8 / 10}, {w / 8, h * 7 / 10}};
}

SpanRows maskSpans(unsigned width, unsigned height, const MaskPainter &painter)
{
    std::vector<glm::dvec2> polygon;
    for (const cv::Point &p : outline(width, height))
        polygon.push_back({p.x, p.y});
    std::vector<RowSpan> spans;
    polygonSpans(polygon, int(width), int(height), spans);
    return SpanRows(std::move(spans), width, height, painter.hSub(), painter.vSub());
}

void overlayBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    OverlayLayer layer(width, height);
    cv::Mat rgba(int(height), int(width), CV_8UC4, layer.data());
    const std::vector<std::vector<cv::Point>> polygons{outline(width, height)};
    cv::fillPoly(rgba, polygons, cv::Scalar(32, 32, 32, 255), cv::LINE_8);
    layer.updateSpans();
    const auto native = NativeLayer::convert(layer, format, Colorimetry{});
    Ring ring(format, width, height);
    size_t i = 0;
    for (auto _ : state) {
        const Status status = native->blend(ring.layout.view(ring.frame(i++)));
        benchmark::DoNotOptimize(status.ok());
    }
    state.counters["area_%"] = 100.0 * double(layer.coveredPixels()) / (width * height);
}

// block 0: a colour fill.
void maskBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height, unsigned block)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    MaskPainter painter(format, Colorimetry{}, width, height);
    const SpanRows spans = maskSpans(width, height, painter);
    Ring ring(format, width, height);
    size_t i = 0;
    for (auto _ : state) {
        const FrameView frame = ring.layout.view(ring.frame(i++));
        if (block)
            painter.pixelate(frame, spans, block);
        else
            painter.fill(frame, spans, Rgba{32, 32, 32, 255});
        benchmark::ClobberMemory();
    }
    state.counters["area_%"] = 100.0 * double(spans.area()) / (width * height);
}

void fillBench(benchmark::State &state, const char *format, unsigned width, unsigned height)
{
    maskBench(state, format, width, height, 0);
}

template<unsigned Block>
void pixelateBench(benchmark::State &state, const char *format, unsigned width, unsigned height)
{
    maskBench(state, format, width, height, Block);
}

constexpr bench::FrameCase kCases[] = {{"YUYV", 1280, 720},   {"NV12", 1280, 720},    {"YUV420", 1280, 720},
                                       {"RGB24", 1280, 720},  {"XRGB32", 1280, 720},  {"GREY", 1280, 720},
                                       {"YUYV", 1920, 1080},  {"NV12", 1920, 1080},   {"YUV420", 1920, 1080},
                                       {"RGB24", 1920, 1080}, {"XRGB32", 1920, 1080}, {"GREY", 1920, 1080}};

struct Kind {
    const char *name;
    bench::FrameBench bench;
};
constexpr Kind kMaskKinds[] = {{"fill", fillBench},
                               {"pixelate8", pixelateBench<8>},
                               {"pixelate16", pixelateBench<16>},
                               {"pixelate32", pixelateBench<32>}};

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    for (const bench::FrameCase &c : kCases) {
        bench::registerCase(kFamily, "opaque_overlay", overlayBench, c);
        for (const Kind &kind : kMaskKinds)
            bench::registerCase(kFamily, kind.name, kind.bench, c);
        bench::registerCase(kFamily, bench::kMemcpyCold, memcpyBench, c);
    }
    const auto reporter = bench::runAll();
    // The claim: a mask costs no more than an opaque overlay of the same area.
    for (const bench::FrameCase &c : kCases) {
        const auto overlay = reporter->cpuSeconds(bench::caseName(kFamily, "opaque_overlay", c));
        const auto copy = reporter->cpuSeconds(bench::caseName(kFamily, bench::kMemcpyCold, c));
        if (overlay && copy)
            std::fprintf(reporter->ratioStream(), "ratio %-18s opaque_overlay / memcpy_cold = %.3f (CPU time)\n",
                         c.name().c_str(), *overlay / *copy);
        for (const Kind &kind : kMaskKinds) {
            const auto mask = reporter->cpuSeconds(bench::caseName(kFamily, kind.name, c));
            if (mask && overlay)
                std::fprintf(reporter->ratioStream(), "ratio %-18s %s / opaque_overlay = %.3f (CPU time)\n",
                             c.name().c_str(), kind.name, *mask / *overlay);
        }
    }
    return 0;
}
