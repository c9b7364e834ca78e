// SPDX-License-Identifier: Apache-2.0
// JpegFeed: the newest JPEG of the stream, handed from the encoding thread to the server on the loop thread. The
// encoder works only while the feed is wanted (a /stream client watches, or a /snapshot waits), once per frame for
// every client; an eventfd wakes the loop when a new JPEG is published.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

struct JpegFrame {
    std::vector<uint8_t> bytes;
    uint64_t sequence = 0;   // the source's frame number
    int64_t timestampUs = 0; // the frame's capture time, CLOCK_MONOTONIC
    uint64_t generation = 0; // counts publications of this kind (overlaid or raw), from 1
};

class JpegFeed
{
public:
    static Result<std::unique_ptr<JpegFeed>> create();

    // The encoder's side (any thread).
    bool wanted() const { return watchers_.load() > 0 || snapshotWaiters_.load() > 0; }
    bool rawWanted() const { return rawWaiters_.load() > 0; }
    void publish(std::vector<uint8_t> bytes, uint64_t sequence, int64_t timestampUs, bool raw);

    // The server's side (the loop thread).
    int wakeFd() const { return wake_.get(); }
    void consumeWake();
    std::shared_ptr<const JpegFrame> latest(bool raw = false) const;
    void setWatchers(unsigned count) { watchers_ = count; }
    void addSnapshotWaiter(bool raw, int delta) { (raw ? rawWaiters_ : snapshotWaiters_) += delta; }
    uint64_t published() const { return published_.load(); }

private:
    explicit JpegFeed(UniqueFd wake) : wake_(std::move(wake)) {}

    UniqueFd wake_;
    std::atomic<unsigned> watchers_{0};
    std::atomic<int> snapshotWaiters_{0}, rawWaiters_{0};
    std::atomic<uint64_t> published_{0};
    mutable std::mutex mutex_;
    std::shared_ptr<const JpegFrame> latest_, latestRaw_;
};

} // namespace overlayd
