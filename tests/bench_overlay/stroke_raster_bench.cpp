// SPDX-License-Identifier: Apache-2.0
// StrokeRasterizer against the OpenCV path it replaces, on the Speed scene's ground grid (40 lines 2 px wide seen by
// the pitched-down camera of scene_bench.cpp) at 1920x1080, the camera yawing between frames:
//   stroke_raster  coverage rows into a sink that sums them (what a frame sink would blend);
//   opencv_fill    cv::fillConvexPoly LINE_AA of each segment's inset quad into a full-frame CV_8UC1 mask, as
//                  overlay/raster/rasterizer.cpp draws a translucent stroke (opencv_fill_clear also clears the mask
//                  after, as that path must before the next item);
//   memcpy         one cold 1920x1080 YUYV frame copy, the floor the targets are measured against.
// ns_per_px is the time per covered pixel (pixels with coverage > 0 in StrokeRasterizer's output).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>

#include "cold_frames.h"
#include "overlay/raster/stroke_raster.h"
#include "projection/camera.h"

namespace overlayd {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;
constexpr double kLineWidth = 2.0;

Camera gridCamera(double yawDeg)
{
    const PinholeIntrinsics k{0.8 * kWidth, 0.8 * kWidth, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0, 0.0,
                              kWidth,       kHeight};
    const auto projection = Projection::pinhole(k, 0.1, 200.0, DepthRange::MinusOneToOne);
    const auto pose = poseFromYawPitchRoll({-6.0, 0.0, 2.5}, yawDeg, 22.0, 0.0);
    const auto viewport = Viewport::create(ViewportSpec{kWidth, kHeight});
    return *Camera::create(*pose, *projection, Distortion{}, *viewport);
}

// 20 + 20 ground lines 0.5 m apart (scene_bench's grid), projected for 16 yaws of the moving camera.
const std::vector<Polylines> &gridFrames()
{
    static const std::vector<Polylines> frames = [] {
        std::vector<Polylines> out;
        for (int f = 0; f < 16; ++f) {
            const Camera camera = gridCamera(0.1 * f - 0.8);
            Polylines lines;
            for (int i = 0; i < 20; ++i) {
                const double c = -4.75 + 0.5 * i;
                camera.projectSegment({c, -4.75, 0, 1}, {c, 4.75, 0, 1}, lines);
                camera.projectSegment({-4.75, c, 0, 1}, {4.75, c, 0, 1}, lines);
            }
            out.push_back(std::move(lines));
        }
        return out;
    }();
    return frames;
}

// What the timed loop emits into: the sum of the coverage (a loop the compiler vectorizes, so that the sink costs
// little next to the rasterizer).
class SumSink final : public CoverageSink
{
public:
    void begin(Rgba) override {}
    void end() override {}
    void row(int, int, const uint8_t *coverage, int count) override
    {
        uint32_t rowSum = 0;
        for (int i = 0; i < count; ++i)
            rowSum += coverage[i];
        sum += rowSum;
    }
    uint64_t sum = 0;
};

// Covered pixels and row() calls per frame, averaged over the frames.
class CountSink final : public CoverageSink
{
public:
    void begin(Rgba) override {}
    void end() override {}
    void row(int, int, const uint8_t *coverage, int count) override
    {
        ++calls;
        for (int i = 0; i < count; ++i)
            covered += coverage[i] != 0;
    }
    double covered = 0, calls = 0;
};

void setCounters(benchmark::State &state)
{
    StrokeRasterizer raster;
    CountSink stats;
    for (const Polylines &lines : gridFrames())
        raster.rasterize(lines, kLineWidth, true, {0, 0}, {0, 0, kWidth, kHeight}, stats);
    const double frames = double(gridFrames().size()), pixels = stats.covered / frames;
    state.counters["covered_px"] = pixels;
    state.counters["row_calls"] = stats.calls / frames;
    state.counters["ns_per_px"] =
        benchmark::Counter(pixels, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void strokeRasterBench(benchmark::State &state)
{
    StrokeRasterizer raster;
    SumSink sink;
    size_t i = 0;
    for (auto _ : state) {
        raster.rasterize(gridFrames()[i++ % gridFrames().size()], kLineWidth, true, {0, 0}, {0, 0, kWidth, kHeight},
                         sink);
        benchmark::DoNotOptimize(sink.sum);
    }
    setCounters(state);
}

// overlay/raster/rasterizer.cpp's stroke: quads inset by 0.675 px (OpenCV's anti-aliased edge adds about that much on
// each side), 8 fractional bits; interior joints overlap by max(half, 1) px.
void fillStrokes(const Polylines &lines, cv::Mat &mask)
{
    constexpr double kOne = 256.0;
    const double half = std::max(0.5 * kLineWidth - 0.675, 0.0);
    const auto fixed = [&](glm::dvec2 p) {
        return cv::Point(int(std::lround(p.x * kOne)), int(std::lround(p.y * kOne)));
    };
    for (size_t l = 0; l < lines.size(); ++l) {
        const auto line = lines[l];
        for (size_t i = 1; i < line.size(); ++i) {
            const glm::dvec2 a = line[i - 1], b = line[i];
            const double length = glm::distance(a, b);
            if (length == 0.0)
                continue;
            const glm::dvec2 d = (b - a) / length, n(-d.y, d.x);
            const double overlap = std::max(half, 1.0);
            const glm::dvec2 a0 = a - (i > 1 ? overlap : 0.0) * d, b0 = b + (i + 1 < line.size() ? overlap : 0.0) * d;
            const cv::Point quad[4] = {fixed(a0 + half * n), fixed(b0 + half * n), fixed(b0 - half * n),
                                       fixed(a0 - half * n)};
            cv::fillConvexPoly(mask, quad, 4, cv::Scalar(255), cv::LINE_AA, 8);
        }
    }
}

void opencvFillBench(benchmark::State &state, bool clear)
{
    cv::Mat mask = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);
    size_t i = 0;
    for (auto _ : state) {
        fillStrokes(gridFrames()[i++ % gridFrames().size()], mask);
        benchmark::DoNotOptimize(mask.data);
        if (clear)
            mask.setTo(0);
        benchmark::ClobberMemory();
    }
    setCounters(state);
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    benchmark::RegisterBenchmark("BM_Stroke/raster/grid/1920x1080", strokeRasterBench)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_Stroke/opencv_fill/grid/1920x1080", opencvFillBench, false)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_Stroke/opencv_fill_clear/grid/1920x1080", opencvFillBench, true)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_Stroke/memcpy_cold/YUYV/1920x1080", bench::memcpyBench, "YUYV", 1920u, 1080u)
        ->Unit(benchmark::kMicrosecond);
    const auto reporter = bench::runAll();
    // Same-run ratios (CPU time: these machines are shared, see docs/speed.md).
    const auto raster = reporter->cpuSeconds("BM_Stroke/raster/grid/1920x1080");
    const auto copy = reporter->cpuSeconds("BM_Stroke/memcpy_cold/YUYV/1920x1080");
    const auto fill = reporter->cpuSeconds("BM_Stroke/opencv_fill/grid/1920x1080");
    const auto fillClear = reporter->cpuSeconds("BM_Stroke/opencv_fill_clear/grid/1920x1080");
    if (raster && copy && fill && fillClear)
        std::fprintf(reporter->ratioStream(),
                     "\nratio raster / memcpy_cold %.2f, opencv_fill / raster %.2f, opencv_fill_clear / raster %.2f\n",
                     *raster / *copy, *fill / *raster, *fillClear / *raster);
    return 0;
}
