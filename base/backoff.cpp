// SPDX-License-Identifier: Apache-2.0
// Backoff: doubling with a ceiling.
#include "base/backoff.h"

#include <algorithm>

namespace overlayd {

Backoff::Backoff(Duration first, Duration ceiling) : first_(first), ceiling_(std::max(first, ceiling)), current_(first)
{}

Backoff::Duration Backoff::next()
{
    const Duration delay = current_;
    current_ = std::min(current_ * 2, ceiling_);
    ++attempts_;
    return delay;
}

void Backoff::reset()
{
    current_ = first_;
    attempts_ = 0;
}

} // namespace overlayd
