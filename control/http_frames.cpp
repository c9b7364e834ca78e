// SPDX-License-Identifier: Apache-2.0
#include "control/http_frames.h"

namespace overlayd {

namespace {

Status encodeInto(std::optional<JpegEncoder> &encoder, JpegFeed &feed, int quality, const FrameView &frame,
                  const FrameMetadata &metadata, bool raw)
{
    if (!encoder) {
        auto created = JpegEncoder::create(JpegChroma::Halved); // what MJPEG viewers get from any server
        if (!created)
            return created.error();
        encoder.emplace(std::move(*created));
    }
    std::vector<uint8_t> jpeg;
    if (auto encoded = encoder->encode(frame, metadata.colorimetry, quality, jpeg); !encoded)
        return encoded;
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(metadata.timestamp).count();
    feed.publish(std::move(jpeg), metadata.sequence, us, raw);
    return Ok{};
}

} // namespace

Status JpegFeedSink::write(const FrameView &frame, const FrameMetadata &metadata)
{
    if (!feed_.wanted())
        return Ok{};
    return encodeInto(encoder_, feed_, quality_.load(), frame, metadata, false);
}

void RawSnapshotTap::operator()(const FrameView &frame, const FrameMetadata &metadata)
{
    if (feed_.rawWanted())
        (void)encodeInto(encoder_, feed_, quality_.load(), frame, metadata, true); // a failure: the wait ends in 503
}

} // namespace overlayd
