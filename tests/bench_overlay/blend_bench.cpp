// SPDX-License-Identifier: Apache-2.0
// Per-frame blend of a cached overlay against a cold memcpy of the same frame, in the same run.
//
// The layer is a grid of anti-aliased 2-pixel lines drawn with OpenCV onto transparent black (which yields
// premultiplied colour), grown until it covers ~9.5% of the pixels, the coverage landscape.md measures. Frames come
// from a ring larger than the caches so that both the blend and the copy start cold.
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cold_frames.h"
#include "overlay/blend/native_layer.h"

namespace overlayd {
namespace {

using bench::memcpyBench;
using bench::Ring;

constexpr double kCoverage = 0.095;

std::unique_ptr<OverlayLayer> gridLayer(unsigned width, unsigned height)
{
    auto layer = std::make_unique<OverlayLayer>(width, height);
    cv::Mat rgba(height, width, CV_8UC4, layer->data());
    const cv::Scalar colours[] = {{255, 60, 0, 255}, {0, 255, 120, 255}, {40, 80, 255, 255}};
    std::vector<cv::Mat> channels;
    for (int k = 0; k < 1000; ++k) {
        // Near-horizontal rungs and lines converging on a vanishing point above the frame, like a ground grid.
        const double t = (k / 2 * 0.618034) - int(k / 2 * 0.618034);
        cv::Point a(0, int(t * height)), b(width - 1, int(t * height) + 7);
        if (k % 2)
            a = {int(width / 2), -int(height)}, b = {int(t * 3 * width - width), int(height) - 1};
        cv::line(rgba, a, b, colours[k % 3], 2, cv::LINE_AA);
        cv::split(rgba, channels);
        if (cv::countNonZero(channels[3]) >= kCoverage * width * height)
            break;
    }
    layer->updateSpans();
    return layer;
}

void blendBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    const auto layer = gridLayer(width, height);
    const auto native = NativeLayer::convert(*layer, format, Colorimetry{});
    Ring ring(format, width, height);
    size_t i = 0;
    for (auto _ : state) {
        const Status status = native->blend(ring.layout.view(ring.frame(i++)));
        benchmark::DoNotOptimize(status.ok());
    }
    state.counters["coverage_%"] = 100.0 * layer->coveredPixels() / (width * height);
    state.counters["touched_bytes"] = native->touchedBytes();
    state.counters["runs"] = native->runs().size();
}

// The cost paid when the overlay changes: converting the layer to the frame's format.
void convertBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    const auto layer = gridLayer(width, height);
    for (auto _ : state) {
        auto native = NativeLayer::convert(*layer, format, Colorimetry{});
        benchmark::DoNotOptimize(native.ok());
    }
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    constexpr const char *kFamily = "BM_GridLayer";
    for (const bench::FrameCase &c : bench::kFrameCases) {
        bench::registerCase(kFamily, "blend", blendBench, c);
        bench::registerCase(kFamily, bench::kMemcpyCold, memcpyBench, c);
        bench::registerCase(kFamily, "convert", convertBench, c);
    }
    bench::printRatiosToMemcpy(*bench::runAll(), kFamily, {"blend"});
    return 0;
}
