// SPDX-License-Identifier: Apache-2.0
// EncodedStream: the daemon's side of the encoded outputs: the feed that copies each overlaid frame once for the
// encoder, and the engine that encodes and serves it. The daemon keeps it for /state and /metrics and hands the
// pipeline a FrameSink over it (sink()), which runs inline on the pipeline's thread: one copy into a free slot,
// or a counted drop, never a wait.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "drivers/frame_sink.h"
#include "stream/encoded_stream_engine.h"
#include "stream/encoder_feed.h"

namespace overlayd {

// What /state and /metrics read: the engine's own state and the feed's counters, taken together.
struct EncodedStreamState {
    EngineState engine;
    FeedCounters feed;
    LatencyHistogram blended; // capture to the overlay blended in (the frame reaching the feed)
};

class EncodedStream : public std::enable_shared_from_this<EncodedStream>
{
public:
    EncodedStream(const StreamOptions &options, std::unique_ptr<EncodedStreamEngine> engine);
    ~EncodedStream();

    // A sink for the pipeline that feeds this stream (it keeps the stream alive).
    std::unique_ptr<FrameSink> sink();
    EncodedStreamState state() const;
    const StreamOptions &options() const { return options_; }
    // "openh264 → rtsp://127.0.0.1:8554/cam"
    std::string describe() const;
    // WebRTC peers (WHEP), the engine's own (encoded_stream_engine.h): callable from any thread.
    Result<WebrtcAnswer> addPeer(const std::string &offer, const std::string &address)
    {
        return engine_->addPeer(offer, address);
    }
    Status removePeer(const std::string &id) { return engine_->removePeer(id); }

    // Where close() reports the frames' account ("encoder X: N frames in: Z zero-copy, C copied, D dropped").
    void setLog(EngineLog log) { log_ = std::move(log); }

    Status open(const StreamFormat &format);
    Status write(const FrameView &frame, const FrameMetadata &metadata);
    // Zero copy: whether the frame goes to the encoder by its DMABUF (writeLease) rather than copied (write).
    bool takesLease(const FrameView &frame) const;
    Status writeLease(std::shared_ptr<const FrameLease> lease);
    void close();

private:
    // The stream's frame time, and the blend latency counted.
    std::chrono::nanoseconds arrived(const FrameMetadata &metadata);

    StreamOptions options_;
    std::unique_ptr<EncodedStreamEngine> engine_;
    EncoderFeed feed_;
    EngineLog log_;
    bool open_ = false;
    bool leases_ = false;             // decided by open(): the encoder imports the capture buffers' DMABUF
    mutable std::mutex latencyMutex_; // write() on the pipeline's thread, state() on the loop's
    LatencyHistogram blended_;
    // Whether the source stamps frames on CLOCK_MONOTONIC (V4L2, libcamera), judged at its first frame; a source
    // whose timestamps count from 0 (synthetic, replay) is measured from the frame reaching this stream.
    std::optional<bool> toMonotonic_;
};

} // namespace overlayd
