// SPDX-License-Identifier: Apache-2.0
// Push state: the back-off restarts from its floor after each connection that worked.
#include "stream/push_link.h"

namespace overlayd {

PushLink::PushLink(Backoff backoff) : backoff_(backoff) {}

void PushLink::connected()
{
    connected_ = true;
    backoff_.reset();
    lastError_.clear();
}

PushLink::Retry PushLink::failed(const std::string &reason)
{
    connected_ = false;
    const bool fresh = reason != lastError_;
    lastError_ = reason;
    return {backoff_.next(), fresh};
}

} // namespace overlayd
