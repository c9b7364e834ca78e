// SPDX-License-Identifier: Apache-2.0
// EncoderFeed: the one place a frame is copied for the encoder, converted to I420 on the way when the stream has
// another format. A bounded set of slots: a slot is with the encoder until the engine drops the EncoderInput that
// holds it (GStreamer lets go of the buffer), and a frame that finds every slot taken is dropped and counted, so
// the pipeline's thread never waits for the encoder.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "base/result.h"
#include "media/convert/images.h"
#include "media/stream.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd {

struct FeedCounters {
    uint64_t copied = 0;    // frames copied into a slot (each one copy)
    uint64_t converted = 0; // of those, frames whose format was converted to I420 on the way
    uint64_t zeroCopy = 0;  // frames handed as the capture buffer's DMABUF (no copy): lease()
    uint64_t dropped = 0;   // frames that found every slot with the encoder
    unsigned inFlight = 0;  // slots with the encoder now
};

class EncoderFeed
{
public:
    explicit EncoderFeed(unsigned slots);
    ~EncoderFeed();
    EncoderFeed(const EncoderFeed &) = delete;
    EncoderFeed &operator=(const EncoderFeed &) = delete;

    // The stream's format: I420 needs an even width and height (what every H.264 encoder takes).
    Result<EngineFormat> open(const StreamFormat &format);
    // The frame copied (and converted) into a free slot, or nullopt: every slot is with the encoder (a drop,
    // counted) or the frame does not convert (logged by the caller from the error it gets next time).
    std::optional<EncoderInput> fill(const FrameView &frame, const FrameMetadata &metadata,
                                     std::chrono::nanoseconds blendedTime);
    // Zero copy: from now on up to `limit` leases may be with the encoder at once (0: none, the default).
    void setLeaseLimit(unsigned limit);
    // The capture buffer itself, by its DMABUF (an I420 frame whose planes share one exported buffer): the input
    // holds the lease until the encoder lets it go. nullopt: `limit` leases are with the encoder (a drop, counted).
    std::optional<EncoderInput> lease(std::shared_ptr<const FrameLease> lease, std::chrono::nanoseconds blendedTime);
    FeedCounters counters() const;

private:
    struct Pool; // shared with the slots' release, which may run on the encoder's thread after the feed is gone
    bool copyInto(uint8_t *slot, const FrameView &frame);

    std::shared_ptr<Pool> pool_;
    unsigned leaseLimit_ = 0;
    StreamFormat format_{};
    Colorimetry colorimetry_{};
    YcbcrImage scratch_;
    RgbImage rgbScratch_;
};

} // namespace overlayd
