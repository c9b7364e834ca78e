// SPDX-License-Identifier: Apache-2.0
// EncodedStream and the FrameSink the pipeline writes it through.
#include "stream/encoded_stream.h"

#include <time.h>

namespace overlayd::stream {
namespace {

std::chrono::nanoseconds monotonicNow()
{
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return std::chrono::seconds(now.tv_sec) + std::chrono::nanoseconds(now.tv_nsec);
}

class EncodedStreamSink : public FrameSink
{
public:
    explicit EncodedStreamSink(std::shared_ptr<EncodedStream> stream) : stream_(std::move(stream)) {}

    Status open(const StreamFormat &format) override { return stream_->open(format); }
    Status write(const FrameView &frame, const FrameMetadata &metadata) override
    {
        return stream_->write(frame, metadata);
    }
    Status close() override
    {
        stream_->close();
        return Ok{};
    }
    std::string describe() const override { return stream_->describe(); }
    // One copy into a free slot or a counted drop: no thread or queue of the sink worker's is needed.
    bool writesInline() const override { return true; }

private:
    std::shared_ptr<EncodedStream> stream_;
};

} // namespace

EncodedStream::EncodedStream(const StreamOptions &options, std::unique_ptr<EncodedStreamEngine> engine)
    : options_(options), engine_(std::move(engine)), feed_(options.encoder.queuedFrames)
{}

EncodedStream::~EncodedStream()
{
    close();
}

std::unique_ptr<FrameSink> EncodedStream::sink()
{
    return std::make_unique<EncodedStreamSink>(shared_from_this());
}

Status EncodedStream::open(const StreamFormat &format)
{
    close();
    toMonotonic_.reset();
    auto engineFormat = feed_.open(format);
    if (!engineFormat)
        return engineFormat.error();
    if (auto opened = engine_->open(*engineFormat); !opened)
        return opened;
    open_ = true;
    return Ok{};
}

Status EncodedStream::write(const FrameView &frame, const FrameMetadata &metadata)
{
    if (!open_)
        return makeError(ErrorCode::InvalidArgument, "the encoder is not open");
    const std::chrono::nanoseconds now = monotonicNow();
    if (!toMonotonic_) // a timestamp more than a minute from the clock is not on it (stream time from 0)
        toMonotonic_ = std::chrono::abs(now - metadata.timestamp) < std::chrono::minutes(1);
    // Such a source's schedule is not its frames' latency: its blend counts as 0.
    const std::chrono::nanoseconds captured = *toMonotonic_ ? metadata.timestamp : now;
    if (now >= captured) {
        std::lock_guard lock(latencyMutex_);
        blended_.add(std::chrono::duration<double>(now - captured).count());
    }
    if (auto input = feed_.fill(frame, metadata, now)) // the source's timestamps stay the stream's PTS
        engine_->push(std::move(*input));
    return Ok{}; // a drop is counted by the feed, not a failure of the sink
}

void EncodedStream::close()
{
    if (open_)
        engine_->close();
    open_ = false;
}

EncodedStreamState EncodedStream::state() const
{
    std::lock_guard lock(latencyMutex_);
    return {engine_->state(), feed_.counters(), blended_};
}

std::string EncodedStream::describe() const
{
    std::string text =
        std::string(codecName(options_.encoder.codec)) + " (" + encoderKindName(options_.encoder.kind) + ")";
    for (const EncodedSinkOptions &sink : options_.sinks)
        if (sink.kind == EncodedSinkKind::Rtsp)
            text += std::string(sink.rtsp.access.certPem.empty() ? " -> rtsp://" : " -> rtsps://") + sink.rtsp.listen +
                    sink.rtsp.path;
    if (options_.webrtc.enabled)
        text += " -> WHEP /whep";
    return text;
}

} // namespace overlayd::stream
