// SPDX-License-Identifier: Apache-2.0
// Cold frames for the overlay benchmarks: a ring of frames larger than the caches, and the baseline every ratio is
// measured against, a cold memcpy of one frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "media/frame.h"
#include "media/pixel_format.h"
#include "tests/bench_support/same_run.h"

namespace overlayd::bench {

inline constexpr size_t kRingBytes = size_t(96) << 20;

struct Ring {
    FrameLayout layout;
    std::vector<uint8_t> bytes;
    size_t count;

    Ring(const PixelFormatInfo &format, unsigned width, unsigned height)
        : layout(*makeFrameLayout(format, width, height)), count(kRingBytes / layout.totalSize + 1)
    {
        bytes.assign(layout.totalSize * count, 0x80);
    }
    uint8_t *frame(size_t i) { return bytes.data() + (i % count) * layout.totalSize; }
};

inline void memcpyBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    Ring ring(*pixelFormatFromName(formatName), width, height);
    size_t i = 0;
    for (auto _ : state) {
        std::memcpy(ring.frame(i + ring.count / 2), ring.frame(i), ring.layout.totalSize);
        benchmark::ClobberMemory();
        ++i;
    }
}

// The formats and sizes the overlay benchmarks time (the issue's), and a case's name: "YUYV/1280x720".
struct FrameCase {
    const char *format;
    unsigned width, height;

    std::string name() const
    {
        return std::string(format) + "/" + std::to_string(width) + "x" + std::to_string(height);
    }
};
inline constexpr FrameCase kFrameCases[] = {
    {"YUYV", 1280, 720}, {"NV12", 1280, 720}, {"YUYV", 1920, 1080}, {"NV12", 1920, 1080}};

using FrameBench = void (*)(benchmark::State &, const char *format, unsigned width, unsigned height);

// The baseline's name in every overlay bench: a memcpy of a frame that is not in the cache.
inline constexpr const char *kMemcpyCold = "memcpy_cold";

// "<family>/<kind>/<case>", e.g. "BM_Blend/static/YUYV/1920x1080".
inline std::string caseName(const char *family, const std::string &kind, const FrameCase &c)
{
    return std::string(family) + "/" + kind + "/" + c.name();
}

// The tail of every overlay bench: one line per case and kind that both ran, its time over the cold memcpy of the
// same frame from the same run (runs drift: only a same-run ratio means much). CPU time first (the steadier figure
// on a shared machine), then wall time (where the two differ, other processes held the core):
// "ratio YUYV/1280x720     blend / memcpy_cold = 0.412 (CPU time; wall 0.430)".
inline void printRatiosToMemcpy(const SameRunReporter &reporter, const char *family,
                                const std::vector<std::string> &kinds)
{
    for (const FrameCase &c : kFrameCases)
        for (const std::string &kind : kinds) {
            const std::string name = caseName(family, kind, c), copy = caseName(family, kMemcpyCold, c);
            const auto cpu = reporter.cpuSeconds(name), copyCpu = reporter.cpuSeconds(copy);
            const auto wall = reporter.wallSeconds(name), copyWall = reporter.wallSeconds(copy);
            if (cpu && copyCpu && wall && copyWall)
                std::fprintf(reporter.ratioStream(), "ratio %-16s %s / %s = %.3f (CPU time; wall %.3f)\n",
                             c.name().c_str(), kind.c_str(), kMemcpyCold, *cpu / *copyCpu, *wall / *copyWall);
        }
}

// Registers bench for one case as caseName(family, kind, c), timed in milliseconds.
inline void registerCase(const char *family, const char *kind, FrameBench bench, const FrameCase &c)
{
    benchmark::internal::Benchmark *b =
        benchmark::RegisterBenchmark(caseName(family, kind, c).c_str(), bench, c.format, c.width, c.height)
            ->Unit(benchmark::kMillisecond);
    // A fixed count instead of a minimum time: instructions/count.sh needs to know how many iterations ran (a timed
    // run also executes its probing rounds, which are not reported).
    if (const char *iterations = std::getenv("OVERLAYD_BENCH_ITERATIONS"))
        b->Iterations(std::max(1LL, std::atoll(iterations)));
}

} // namespace overlayd::bench
