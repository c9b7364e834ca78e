// SPDX-License-Identifier: Apache-2.0
// What every benchmark executable of the project shares: Google Benchmark's own reporters (so that
// --benchmark_format=json and --benchmark_out=FILE --benchmark_out_format=json give the standard output that
// scripts/bench_table.py reads) plus each case's time per iteration, kept for the same-run ratios printed at the end.
//
// Only same-run ratios mean much on these shared machines (runs drift by up to 1.5x), so every bench times its
// baseline (OpenCV, a cold memcpy, the RGB round trip) in the same process and prints "ratio" lines from the runs.
#pragma once

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace overlayd::bench {

// Forwards everything to the display reporter --benchmark_format asks for (a custom reporter handed to
// RunSpecifiedBenchmarks as display reporter would replace it, and --benchmark_format=json would print a table)
// and records the time per iteration of every run.
class SameRunReporter : public benchmark::BenchmarkReporter
{
public:
    SameRunReporter() : display_(benchmark::CreateDefaultDisplayReporter()) {}

    bool ReportContext(const Context &context) override { return display_->ReportContext(context); }
    void ReportRuns(const std::vector<Run> &runs) override
    {
        for (const Run &run : runs) {
            if (run.error_occurred)
                continue;
            // Keyed without the "/process_time" or "/real_time" that MeasureProcessCPUTime() and UseRealTime()
            // append: a bench asks for its case by the name it registered (pipeline_bench printed no ratio at all
            // while the lookup carried the suffix).
            benchmark::BenchmarkName name = run.run_name;
            name.time_type.clear();
            Times &times = times_[name.str()];
            const double toSeconds = 1.0 / benchmark::GetTimeUnitMultiplier(run.time_unit);
            if (run.run_type == Run::RT_Iteration) {
                times.wall.push_back(run.GetAdjustedRealTime() * toSeconds);
                times.cpu.push_back(run.GetAdjustedCPUTime() * toSeconds);
            } else if (run.aggregate_name == "median") {
                // With --benchmark_report_aggregates_only the repetitions themselves never reach a reporter.
                times.wallMedian = run.GetAdjustedRealTime() * toSeconds;
                times.cpuMedian = run.GetAdjustedCPUTime() * toSeconds;
            }
        }
        display_->ReportRuns(runs);
    }
    void Finalize() override { display_->Finalize(); }

    // Seconds per iteration of a case (its name without the repetition or aggregate suffix), the median over
    // --benchmark_repetitions; nothing if it did not run (filtered out, or not available on this CPU). CPU time
    // is the steadier figure on a shared machine (time spent descheduled does not count).
    std::optional<double> cpuSeconds(const std::string &name) const
    {
        return find(name, &Times::cpu, &Times::cpuMedian);
    }
    std::optional<double> wallSeconds(const std::string &name) const
    {
        return find(name, &Times::wall, &Times::wallMedian);
    }

    // Where the ratio lines go: stdout under the console reporter, stderr when stdout carries JSON or CSV.
    std::FILE *ratioStream() const
    {
        return dynamic_cast<benchmark::ConsoleReporter *>(display_.get()) ? stdout : stderr;
    }

private:
    struct Times {
        std::vector<double> wall, cpu;
        std::optional<double> wallMedian, cpuMedian;
    };

    std::optional<double> find(const std::string &name, std::vector<double> Times::*runs,
                               std::optional<double> Times::*median) const
    {
        const auto it = times_.find(name);
        if (it == times_.end())
            return std::nullopt;
        if ((it->second.*median).has_value())
            return it->second.*median;
        std::vector<double> values = it->second.*runs;
        if (values.empty())
            return std::nullopt;
        std::sort(values.begin(), values.end());
        const std::size_t n = values.size();
        return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
    }

    std::unique_ptr<benchmark::BenchmarkReporter> display_;
    std::map<std::string, Times> times_;
};

// benchmark::Initialize, refusing unknown arguments (after Google Benchmark's message). Comes before any
// SameRunReporter is made: the display reporter is the one the parsed --benchmark_format names.
inline bool initialize(int &argc, char **argv)
{
    benchmark::Initialize(&argc, argv);
    return !benchmark::ReportUnrecognizedArguments(argc, argv);
}

// Runs every registered case (as --benchmark_filter selects) and returns their times for the ratios.
inline std::unique_ptr<SameRunReporter> runAll()
{
    auto reporter = std::make_unique<SameRunReporter>();
    benchmark::RunSpecifiedBenchmarks(reporter.get());
    benchmark::Shutdown();
    return reporter;
}

} // namespace overlayd::bench
