// SPDX-License-Identifier: Apache-2.0
// RequestRecycler: how a lent libcamera request goes back to the camera, from whichever thread drops the lease.
#pragma once

#include <functional>
#include <mutex>
#include <optional>

#include "base/result.h"
#include "media/stream.h"

namespace overlayd {

// A zero-copy sink drops its lease on its own thread when the output device is done with the buffer, so the
// re-queue runs there: Camera::queueRequest is thread-safe, and one mutex orders give-backs against detach(). The
// seam is `queue` (in production: end CPU access, Request::reuse, Camera::queueRequest), so the bookkeeping is
// tested without a camera.
class RequestRecycler : public LeaseOwner
{
public:
    // `queue(index)` re-queues request `index`; a negative errno is kept for takeError().
    explicit RequestRecycler(std::function<int(unsigned)> queue) : queue_(std::move(queue)) {}
    RequestRecycler(const RequestRecycler &) = delete;
    RequestRecycler &operator=(const RequestRecycler &) = delete;

    void giveBack(unsigned index) override;
    // The first failed re-queue since the last call (the camera went away): the source reports it as DeviceLost.
    std::optional<Error> takeError();
    // Requests lent and not yet given back.
    unsigned lent();
    void lend();
    // The camera stops: waits for a give-back in progress and makes later ones no-ops.
    void detach();

private:
    std::mutex mutex_;
    std::function<int(unsigned)> queue_;
    bool detached_ = false;
    unsigned lent_ = 0;
    std::optional<Error> error_;
};

} // namespace overlayd
