// Cold frames for the overlay benchmarks: a ring of frames larger than the caches, and the baseline every ratio is
// measured against, a cold memcpy of one frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "media/frame.h"
#include "media/pixel_format.h"

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

// Registers bench for one case as "<kind>/<case>", timed in milliseconds.
inline benchmark::internal::Benchmark *registerCase(const char *kind, FrameBench bench, const FrameCase &c)
{
    benchmark::internal::Benchmark *b =
        benchmark::RegisterBenchmark((std::string(kind) + "/" + c.name()).c_str(), bench, c.format, c.width, c.height)
            ->Unit(benchmark::kMillisecond);
    // A fixed count instead of a minimum time: instructions/count.sh needs to know how many iterations ran (a timed
    // run also executes its probing rounds, which are not reported).
    if (const char *iterations = std::getenv("OVERLAYD_BENCH_ITERATIONS"))
        b->Iterations(std::max(1LL, std::atoll(iterations)));
    return b;
}

// The console reporter that also prints same-run ratios at the end (runs drift, so only a same-run ratio means
// much): every run whose name starts with `prefix` against the run `baselineOf` names for it, if there is one
// (of repetitions, the medians only).
class SameRunRatios : public benchmark::ConsoleReporter
{
public:
    enum Clock { Real, Cpu };
    SameRunRatios(std::string prefix, std::string (*baselineOf)(const std::string &name), const char *label,
                  Clock clock = Real)
        : prefix_(std::move(prefix)), baselineOf_(baselineOf), label_(label), clock_(clock)
    {}
    void ReportRuns(const std::vector<Run> &runs) override
    {
        for (const Run &run : runs)
            seconds_[run.benchmark_name()] = clock_ == Real ? run.GetAdjustedRealTime() : run.GetAdjustedCPUTime();
        ConsoleReporter::ReportRuns(runs);
    }
    void Finalize() override
    {
        ConsoleReporter::Finalize();
        for (const auto &[name, time] : seconds_) {
            const bool aggregate = name.find('_', name.rfind('/')) != std::string::npos;
            if (name.rfind(prefix_, 0) != 0 || (aggregate && !name.ends_with("_median")))
                continue;
            const auto baseline = seconds_.find(baselineOf_(name));
            if (baseline != seconds_.end())
                std::printf("%-48s %s = %.3f\n", name.c_str(), label_, time / baseline->second);
        }
    }

private:
    std::string prefix_;
    std::string (*baselineOf_)(const std::string &name);
    const char *label_;
    Clock clock_;
    std::map<std::string, double> seconds_;
};

// Google Benchmark's main, with a reporter that prints the same-run ratios at the end.
inline int runBenchmarks(int argc, char **argv, benchmark::BenchmarkReporter &reporter)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}

} // namespace overlayd::bench
