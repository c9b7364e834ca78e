// SPDX-License-Identifier: Apache-2.0
// The README's demo scene (config/examples/demo.toml, read through the config loader: grid, axes, labels, a
// timestamp and a frame counter, both on translucent boxes) blended on cold frames as the daemon does it, frame
// number and wall clock advancing like a 30 fps camera's, timed from the 300th frame on:
//   BM_Text/demo/...             the whole scene: the counter is new on every frame, the timestamp every 30th;
//   BM_Text/demo_no_counter/...  the same scene without the frame counter;
//   BM_Text/demo_no_text/...     without the timestamp and the counter;
//   BM_Text/memcpy_cold/...      one cold frame copy, the baseline.
// The ratio lines say what share of the demo's blend its frame counter (and its two texts) take: issue 20's target is
// under 10% for the counter (before the glyph cache: more than half).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cold_frames.h"
#include "config/daemon_config.h"
#include "overlay/scene_renderer.h"

#ifndef OVERLAYD_DEMO_CONFIG
#error "OVERLAYD_DEMO_CONFIG must name config/examples/demo.toml"
#endif

namespace overlayd {
namespace {

using bench::Ring;

// The demo's renderer without the annotations named in leaveOut; nullptr (the case skipped) if it cannot be made.
std::unique_ptr<OverlayRenderer> demoRenderer(benchmark::State &state, const std::vector<std::string> &leaveOut,
                                              const char *formatName, unsigned width, unsigned height)
{
    std::vector<ConfigProblem> problems;
    Result<DaemonConfig> config = loadConfigFile(OVERLAYD_DEMO_CONFIG, problems);
    if (!config) {
        state.SkipWithError(config.error().message.c_str());
        return nullptr;
    }
    std::erase_if(config->scene.annotations, [&](const Annotation &a) {
        return std::find(leaveOut.begin(), leaveOut.end(), a.name) != leaveOut.end();
    });
    Result<Camera> camera = config->camera.build(width, height);
    StreamFormat format;
    format.format = pixelFormatFromName(formatName);
    format.width = width;
    format.height = height;
    format.colorimetry = config->source.colorimetry.value_or(Colorimetry{});
    auto renderer = camera ? SceneRenderer::create(config->scene, *camera, format)
                           : Result<std::unique_ptr<OverlayRenderer>>(camera.error());
    if (!renderer) {
        state.SkipWithError(renderer.error().message.c_str());
        return nullptr;
    }
    return std::move(*renderer);
}

// Frame i of a 30 fps stream: its number and its wall-clock time.
FrameMetadata frameAt(size_t i)
{
    FrameMetadata metadata;
    metadata.sequence = i;
    metadata.wallClock =
        std::chrono::system_clock::time_point(std::chrono::milliseconds(1'700'000'000'000 + i * 1000 / 30));
    return metadata;
}

void demoBench(benchmark::State &state, const std::vector<std::string> &leaveOut, const char *formatName,
               unsigned width, unsigned height)
{
    const auto renderer = demoRenderer(state, leaveOut, formatName, width, height);
    if (!renderer)
        return;
    Ring ring(*pixelFormatFromName(formatName), width, height);
    size_t i = 0;
    // Past the first 10 s, as a running daemon is: the layers rendered, and the counter's glyphs stamped at each of
    // their places (its units and tens have shown every digit; the hundreds add one glyph every 100 frames).
    constexpr size_t kWarmUpFrames = 300;
    for (; i < kWarmUpFrames; ++i)
        if (!renderer->blend(ring.layout.view(ring.frame(i)), frameAt(i), 30.0)) {
            state.SkipWithError("the demo scene does not blend");
            return;
        }
    for (auto _ : state) {
        benchmark::DoNotOptimize(renderer->blend(ring.layout.view(ring.frame(i)), frameAt(i), 30.0).ok());
        ++i;
    }
}

void wholeDemo(benchmark::State &state, const char *format, unsigned width, unsigned height)
{
    demoBench(state, {}, format, width, height);
}

void demoWithoutCounter(benchmark::State &state, const char *format, unsigned width, unsigned height)
{
    demoBench(state, {"frame counter"}, format, width, height);
}

void demoWithoutText(benchmark::State &state, const char *format, unsigned width, unsigned height)
{
    demoBench(state, {"frame counter", "timestamp"}, format, width, height);
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    constexpr const char *kFamily = "BM_Text";
    for (const bench::FrameCase &c : bench::kFrameCases) {
        bench::registerCase(kFamily, bench::kMemcpyCold, bench::memcpyBench, c);
        bench::registerCase(kFamily, "demo", wholeDemo, c);
        bench::registerCase(kFamily, "demo_no_counter", demoWithoutCounter, c);
        bench::registerCase(kFamily, "demo_no_text", demoWithoutText, c);
    }
    const auto reporter = bench::runAll();

    std::FILE *out = reporter->ratioStream();
    std::fprintf(out, "\n%-22s %14s %22s %20s\n", "case", "demo/memcpy", "counter share (<0.1)", "both texts' share");
    for (const bench::FrameCase &c : bench::kFrameCases) {
        const auto get = [&](const char *kind) {
            return reporter->cpuSeconds(bench::caseName(kFamily, kind, c)).value_or(0.0);
        };
        const double copy = get(bench::kMemcpyCold), demo = get("demo"), noCounter = get("demo_no_counter"),
                     noText = get("demo_no_text");
        if (copy == 0.0 || demo == 0.0)
            continue;
        std::fprintf(out, "%-22s %14.3f %22.3f %20.3f\n", c.name().c_str(), demo / copy, (demo - noCounter) / demo,
                     (demo - noText) / demo);
    }
    return 0;
}
