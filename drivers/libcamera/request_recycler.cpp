// SPDX-License-Identifier: Apache-2.0
// RequestRecycler: give-backs from any thread, none after detach().
#include "drivers/libcamera/request_recycler.h"

#include <cstring>
#include <string>

namespace overlayd {

void RequestRecycler::giveBack(unsigned index)
{
    std::lock_guard lock(mutex_);
    if (lent_ > 0)
        --lent_;
    if (detached_)
        return;
    if (const int r = queue_(index); r < 0 && !error_)
        error_ = Error{ErrorCode::DeviceLost, "re-queueing request " + std::to_string(index) +
                                                  " failed: " + std::strerror(-r) + " (the camera went away?)"};
}

std::optional<Error> RequestRecycler::takeError()
{
    std::lock_guard lock(mutex_);
    return std::exchange(error_, std::nullopt);
}

unsigned RequestRecycler::lent()
{
    std::lock_guard lock(mutex_);
    return lent_;
}

void RequestRecycler::lend()
{
    std::lock_guard lock(mutex_);
    ++lent_;
}

void RequestRecycler::detach()
{
    std::lock_guard lock(mutex_);
    detached_ = true;
}

} // namespace overlayd
