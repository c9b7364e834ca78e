// SPDX-License-Identifier: Apache-2.0
// The pipeline's own cost with no annotations: a frame lent by a source (from a ring of frames larger than the
// caches, as a camera's buffers are cold) goes through Pipeline::process to its sinks, against a cold memcpy of one
// frame in the same run. Issue 20's goal: at most 1.3x one frame copy.
//
//   BM_Pipeline/no_overlay/null/...        a null sink: written inline, no copy
//   BM_Pipeline/no_overlay/queued/...      a sink that does nothing on its own thread: the queued copy and the
//                                          hand-over every file sink pays, without the sink's own I/O
//   BM_Pipeline/no_overlay/raw_devnull/... a raw sink on /dev/null: the same plus its write() calls (one per row)
//   BM_Pipeline/memcpy_cold/...            one cold frame copy, the baseline
// Timed as the process's CPU time (the sink's thread included), which also keeps other jobs on a shared machine
// out of the figures; the ratios printed at the end are of CPU times.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cold_frames.h"
#include "daemon/pipeline.h"

namespace overlayd {
namespace {

using bench::Ring;

// Queued like every file sink, writes nothing.
struct QueuedNothingSink final : FrameSink {
    Status open(const StreamFormat &) override { return Ok{}; }
    Status write(const FrameView &, const FrameMetadata &) override { return Ok{}; }
    Status close() override { return Ok{}; }
    std::string describe() const override { return "queued nothing"; }
};

// Takes the ring's frames back: nothing to do, like a camera whose buffers are requeued.
struct RingOwner final : LeaseOwner {
    void giveBack(unsigned) override {}
};

void pipelineBench(benchmark::State &state, const char *sinkKind, const char *formatName, unsigned width,
                   unsigned height)
{
    const PixelFormatInfo &format = *pixelFormatFromName(formatName);
    Ring ring(format, width, height);
    Logger logger{[](std::string_view) {}, true};
    Pipeline pipeline(logger);
    SinkOptions options;
    options.kind = std::string(sinkKind) == "null" ? SinkKind::Null : SinkKind::Raw;
    options.path = "/dev/null";
    std::unique_ptr<FrameSink> sink = std::string(sinkKind) == "queued" ? std::make_unique<QueuedNothingSink>()
                                                                        : std::move(makeSink(options).value());
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    sinks.push_back(std::make_unique<SinkWorker>(std::move(sink), options, logger));
    pipeline.setSinks(std::move(sinks));
    StreamFormat stream;
    stream.format = &format;
    stream.width = width;
    stream.height = height;
    stream.fps = 30.0;
    if (!pipeline.openSinks(stream)) {
        state.SkipWithError("cannot open the sink");
        return;
    }
    const auto owner = std::make_shared<RingOwner>();
    FrameMetadata metadata;
    size_t i = 0;
    for (auto _ : state) {
        metadata.sequence = i;
        pipeline.process(FrameLease(ring.layout.view(ring.frame(i)), metadata, owner, 0));
        ++i;
    }
    pipeline.closeSinks(); // waits for queued writes, so the next case starts quiet
    const SinkCounters counters = pipeline.sinks().front()->counters();
    state.counters["dropped"] = double(counters.dropped);
    state.counters["frames_allocated"] = double(pipeline.sinks().front()->allocatedFrames());
}

} // namespace
} // namespace overlayd

int main(int argc, char **argv)
{
    using namespace overlayd;
    if (!bench::initialize(argc, argv))
        return 1;
    constexpr const char *kFamily = "BM_Pipeline";
    constexpr const char *kSinks[] = {"null", "queued", "raw_devnull"};
    for (const bench::FrameCase &c : bench::kFrameCases) {
        for (const char *sink : kSinks)
            benchmark::RegisterBenchmark(bench::caseName(kFamily, std::string("no_overlay/") + sink, c).c_str(),
                                         pipelineBench, sink, c.format, c.width, c.height)
                ->Unit(benchmark::kMillisecond)
                ->MeasureProcessCPUTime();
        benchmark::RegisterBenchmark(bench::caseName(kFamily, bench::kMemcpyCold, c).c_str(), bench::memcpyBench,
                                     c.format, c.width, c.height)
            ->Unit(benchmark::kMillisecond)
            ->MeasureProcessCPUTime();
    }
    // Each sink's pipeline against one cold frame copy, in process CPU time (the sink's thread included).
    std::vector<std::string> kinds;
    for (const char *sink : kSinks)
        kinds.push_back(std::string("no_overlay/") + sink);
    bench::printRatiosToMemcpy(*bench::runAll(), kFamily, kinds);
    return 0;
}
