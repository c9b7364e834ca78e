// SPDX-License-Identifier: Apache-2.0
// Pipeline: a source's frame is blended in place by the stream's overlay, then handed to every sink's worker.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/logger.h"
#include "daemon/sink_worker.h"
#include "overlay/overlay_renderer.h"

namespace overlayd {

// What happened since the previous takeStats(), for the periodic stats line and STATUS=.
struct PipelineStats {
    std::chrono::steady_clock::duration period{0};
    uint64_t framesIn = 0;
    std::chrono::nanoseconds blendTime{0}, pushTime{0};
    struct Sink {
        std::string name;
        SinkCounters counters; // since the previous takeStats
    };
    std::vector<Sink> sinks;
    uint64_t totalDrops = 0; // all sinks, since the pipeline started
    // How the period's last frame was exposed, when its camera says (libcamera)
    std::optional<int32_t> exposureUs;
    std::optional<float> analogueGain;

    // "in 30.0 fps, blend 0.42 ms, queue 0.31 ms; out/demo.y4m: out 30.0 fps, 0 dropped, 0 failed, write 1.20 ms"
    // (a zero-copy sink adds ", 300 zero-copy": frames it took as leases; a camera that reports exposure adds
    // ", exposure 10000 us, gain 1.00" after the queue time)
    std::string describe() const;
};

class Pipeline
{
public:
    explicit Pipeline(Logger &logger) : logger_(logger), lastStats_(std::chrono::steady_clock::now()) {}
    ~Pipeline() { closeSinks(); }

    // The renderer may be null (no annotations, or a NO SIGNAL stream); replacing it happens between two frames.
    void setRenderer(std::unique_ptr<OverlayRenderer> renderer) { renderer_ = std::move(renderer); }
    bool hasRenderer() const { return renderer_ != nullptr; }
    // The renderer frames are blended with, for SceneControl's changes (owned here).
    OverlayRenderer *renderer() { return renderer_.get(); }
    // Called with every source frame after its privacy masks and before the overlay is blended into it (the HTTP
    // server's raw snapshots).
    using FrameTap = std::function<void(const FrameView &, const FrameMetadata &)>;
    void setRawTap(FrameTap tap) { rawTap_ = std::move(tap); }
    // Replaces the sinks; the old ones are flushed and closed first.
    void setSinks(std::vector<std::unique_ptr<SinkWorker>> sinks);
    // (Re)opens every sink for a stream format; returns the first failure, after trying all.
    Status openSinks(const StreamFormat &format);
    // A reload's sinks take over from the running ones, every one open for `format` (the new stream's or the running
    // one's), or none of them: on failure the running sinks run on as they were and the error names the sink
    // (replaceSinks in pipeline.cpp says in which order they open). A running sink that `keep` picks is not
    // replaced: it goes on open (re-opened only for a new format) and joins the new sinks, after them.
    using KeepSink = std::function<bool(const SinkWorker &)>;
    Status replaceSinks(std::vector<std::unique_ptr<SinkWorker>> sinks, const StreamFormat &format,
                        const KeepSink &keep = {});
    // The running sinks for the stream format a reload's new source negotiated; when one cannot take it, every sink
    // is opened for the running format again and the error names the sink.
    Status reopenSinks(const StreamFormat &format);
    void closeSinks();
    const StreamFormat &format() const { return format_; }
    size_t sinkCount() const { return sinks_.size(); }
    const std::vector<std::unique_ptr<SinkWorker>> &sinks() const { return sinks_; }

    // Frame path: blend in place, queue to every sink. A blend failure is logged and the frame still goes out.
    void process(const FrameView &frame, const FrameMetadata &metadata);
    // The same for a source's lease: zero-copy sinks keep a reference to it (the last one gives the buffer back to
    // the source, maybe on a sink's thread), the others get copies before this returns.
    void process(FrameLease lease);
    // Straight to the sinks without the overlay (NO SIGNAL frames).
    void pushToSinks(const FrameView &frame, const FrameMetadata &metadata);

    uint64_t framesIn() const { return framesInTotal_; }
    PipelineStats takeStats();

private:
    // The running sinks open for the running format again, after a reload gave up (failures are logged).
    void restoreSinks();
    // Masks, raw tap, overlay; false when the frame could not be masked and must not go out.
    bool blend(const FrameView &frame, const FrameMetadata &metadata);
    void countFrame(const FrameMetadata &metadata, std::chrono::steady_clock::time_point start,
                    std::chrono::steady_clock::time_point blended);

    Logger &logger_;
    std::unique_ptr<OverlayRenderer> renderer_;
    FrameTap rawTap_;
    std::vector<std::unique_ptr<SinkWorker>> sinks_;
    StreamFormat format_{};

    uint64_t framesInTotal_ = 0;
    uint64_t framesIn_ = 0;
    std::chrono::nanoseconds blendTime_{0}, pushTime_{0};
    std::optional<int32_t> lastExposureUs_;
    std::optional<float> lastAnalogueGain_;
    std::chrono::steady_clock::time_point lastStats_;
    std::vector<SinkCounters> lastCounters_;
    uint64_t retiredDrops_ = 0; // drops of sinks that were replaced
};

} // namespace overlayd
