// SPDX-License-Identifier: Apache-2.0
// LeaseHub: the capture queue's operations, serialized between the event loop and sink threads.
#include "drivers/v4l2/lease_hub.h"

#include <cerrno>

namespace overlayd {

void LeaseHub::giveBack(unsigned index)
{
    std::lock_guard lock(mutex_);
    if (!pool_)
        return;
    if (auto queued = pool_->queue(index); !queued && !pendingError_)
        pendingError_ = queued.error();
}

Status LeaseHub::queue(unsigned index)
{
    std::lock_guard lock(mutex_);
    if (!pool_)
        return makeError(ErrorCode::DeviceLost, "the capture stream was stopped");
    return pool_->queue(index);
}

int LeaseHub::dequeue(Dequeued &out)
{
    std::lock_guard lock(mutex_);
    return pool_ ? pool_->dequeue(out) : -EINVAL;
}

unsigned LeaseHub::queuedCount()
{
    std::lock_guard lock(mutex_);
    return pool_ ? pool_->queuedCount() : 0;
}

std::optional<Error> LeaseHub::takeError()
{
    std::lock_guard lock(mutex_);
    return std::exchange(pendingError_, std::nullopt);
}

void LeaseHub::detach()
{
    std::lock_guard lock(mutex_);
    pool_ = nullptr;
}

} // namespace overlayd
