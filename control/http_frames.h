// SPDX-License-Identifier: Apache-2.0
// The HTTP server's frames: a sink that encodes the overlaid stream to JPEG on its own worker thread (only while the
// feed is wanted: nobody watching costs nothing), and the raw tap that encodes a frame before the overlay when a
// `/snapshot?raw=1` waits for one.
#pragma once

#include <atomic>
#include <memory>

#include "drivers/frame_sink.h"
#include "http/jpeg_feed.h"
#include "media/jpeg/jpeg_encoder.h"

namespace overlayd {

class JpegFeedSink : public FrameSink
{
public:
    JpegFeedSink(JpegFeed &feed, const std::atomic<int> &quality) : feed_(feed), quality_(quality) {}

    Status open(const StreamFormat &) override { return Ok{}; }
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override { return Ok{}; }
    std::string describe() const override { return "http jpeg"; }

private:
    JpegFeed &feed_;
    const std::atomic<int> &quality_;
    std::optional<JpegEncoder> encoder_; // made on the worker thread's first frame
};

// Encodes `frame` for the feed's raw slot when a raw snapshot waits; on the loop thread, before the blend. Rare (a
// person aligning asks for it), so it costs one encode on the frame path only then.
class RawSnapshotTap
{
public:
    RawSnapshotTap(JpegFeed &feed, const std::atomic<int> &quality) : feed_(feed), quality_(quality) {}
    void operator()(const FrameView &frame, const FrameMetadata &metadata);

private:
    JpegFeed &feed_;
    const std::atomic<int> &quality_;
    std::optional<JpegEncoder> encoder_;
};

} // namespace overlayd
