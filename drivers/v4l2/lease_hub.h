// SPDX-License-Identifier: Apache-2.0
// LeaseHub: what a V4L2 capture source shares with the leases it lent: the give-back path and the exported fds.
#pragma once

#include <mutex>
#include <optional>
#include <vector>

#include "base/result.h"
#include "base/unique_fd.h"
#include "drivers/v4l2/buffer_pool.h"
#include "media/stream.h"

namespace overlayd {

// A zero-copy sink drops its lease reference on its own thread, when the output device is done with the buffer, so
// the give-back (VIDIOC_QBUF) runs there and not on the event loop: every use of the pool's queue goes through one
// mutex. Handing indices back to the loop through an eventfd would need a second fd in FrameSource, and when the
// sinks held every buffer the capture fd would never wake the loop to collect them. The kernel serializes the
// ioctls of one queue anyway; the lock guards our bookkeeping and the pool's lifetime (stop() detaches it).
// Leases own a reference to the hub, so the exported dmabuf fds stay open (their numbers valid) while any lease
// is out, even after the source stopped.
class LeaseHub : public LeaseOwner
{
public:
    LeaseHub(BufferPool &pool, std::vector<UniqueFd> dmabufs) : pool_(&pool), dmabufs_(std::move(dmabufs)) {}
    LeaseHub(const LeaseHub &) = delete;
    LeaseHub &operator=(const LeaseHub &) = delete;

    // VIDIOC_QBUF of a buffer given back; a failure (device gone) is kept for takeError(). Nothing after detach().
    void giveBack(unsigned index) override;
    Status queue(unsigned index);
    int dequeue(Dequeued &out);
    unsigned queuedCount();
    std::optional<Error> takeError();
    // Before the pool is freed: waits for a give-back in progress, and makes later ones no-ops.
    void detach();

private:
    std::mutex mutex_;
    BufferPool *pool_;
    std::vector<UniqueFd> dmabufs_;
    std::optional<Error> pendingError_;
};

} // namespace overlayd
