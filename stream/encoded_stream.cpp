// SPDX-License-Identifier: Apache-2.0
// EncodedStream and the FrameSink the pipeline writes it through.
#include "stream/encoded_stream.h"

#include <time.h>

#include <algorithm>

namespace overlayd {
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
    bool takesLease(const FrameView &frame) const override { return stream_->takesLease(frame); }
    Status writeLease(std::shared_ptr<const FrameLease> lease) override
    {
        return stream_->writeLease(std::move(lease));
    }
    // One copy into a free slot or a counted drop: no thread or queue of the sink worker's is needed.
    bool writesInline() const override { return true; }

private:
    std::shared_ptr<EncodedStream> stream_;
};

// Why the capture buffers cannot go to the encoder by DMABUF, or empty when they can (as far as the stream's format
// tells: the engine says next whether its encoder imports them).
std::string whyNoDmabuf(const StreamFormat &format)
{
    if (format.dmabufBuffers == 0)
        return "the source exports no DMABUF buffers (a [source] kind = \"v4l2\" capture, not MJPEG, exports them)";
    if (format.format->name != "YUV420")
        return "the encoder imports I420 frames ([source] format = \"YUV420\"), the source gives " +
               std::string(format.format->name);
    if (format.dmabufBuffers < 3)
        return "the source has " + std::to_string(format.dmabufBuffers) + " buffers, it keeps 2 to capture into";
    return {};
}

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
    std::string whyNot = whyNoDmabuf(format);
    engineFormat->dmabuf = options_.encoder.zeroCopy != EncoderZeroCopy::Off && whyNot.empty();
    if (auto opened = engine_->open(*engineFormat); !opened)
        return opened;
    leases_ = engineFormat->dmabuf && engine_->state().dmabufImport;
    if (engineFormat->dmabuf && !leases_)
        whyNot = "the encoder " + engine_->state().encoder + " is not a V4L2 M2M encoder";
    if (options_.encoder.zeroCopy == EncoderZeroCopy::On && !leases_) {
        engine_->close();
        return makeError(ErrorCode::Unsupported, "[encoder] zero_copy = \"on\": " + whyNot);
    }
    // The capture keeps 2 of its buffers; the encoder may hold the others, up to its queue.
    feed_.setLeaseLimit(leases_ ? std::min(options_.encoder.queuedFrames, format.dmabufBuffers - 2) : 0);
    open_ = true;
    return Ok{};
}

Status EncodedStream::write(const FrameView &frame, const FrameMetadata &metadata)
{
    if (!open_)
        return makeError(ErrorCode::InvalidArgument, "the encoder is not open");
    if (auto input = feed_.fill(frame, metadata, arrived(metadata))) // the source's timestamps stay the stream's PTS
        engine_->push(std::move(*input));
    return Ok{}; // a drop is counted by the feed, not a failure of the sink
}

bool EncodedStream::takesLease(const FrameView &frame) const
{
    if (!open_ || !leases_ || frame.format == nullptr || frame.format->name != "YUV420")
        return false;
    const int fd = frame.planes[0].dmabufFd;
    return fd >= 0 && frame.planes[1].dmabufFd == fd && frame.planes[2].dmabufFd == fd;
}

Status EncodedStream::writeLease(std::shared_ptr<const FrameLease> lease)
{
    if (!open_)
        return makeError(ErrorCode::InvalidArgument, "the encoder is not open");
    const std::chrono::nanoseconds now = arrived(lease->metadata());
    if (auto input = feed_.lease(std::move(lease), now))
        engine_->push(std::move(*input));
    return Ok{}; // a drop is counted by the feed
}

std::chrono::nanoseconds EncodedStream::arrived(const FrameMetadata &metadata)
{
    const std::chrono::nanoseconds now = monotonicNow();
    if (!toMonotonic_) // a timestamp more than a minute from the clock is not on it (stream time from 0)
        toMonotonic_ = std::chrono::abs(now - metadata.timestamp) < std::chrono::minutes(1);
    // Such a source's schedule is not its frames' latency: its blend counts as 0.
    const std::chrono::nanoseconds captured = *toMonotonic_ ? metadata.timestamp : now;
    if (now >= captured) {
        std::lock_guard lock(latencyMutex_);
        blended_.add(std::chrono::duration<double>(now - captured).count());
    }
    return now;
}

void EncodedStream::close()
{
    if (open_) {
        const std::string encoder = engine_->state().encoder;
        engine_->close();
        const FeedCounters feed = feed_.counters();
        if (log_)
            log_(kLogInfo, "encoder " + encoder + ": " + std::to_string(feed.zeroCopy + feed.copied) +
                               " frames in: " + std::to_string(feed.zeroCopy) + " zero-copy, " +
                               std::to_string(feed.copied) + " copied, " + std::to_string(feed.dropped) + " dropped");
    }
    open_ = false;
    leases_ = false;
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

} // namespace overlayd
