// SPDX-License-Identifier: Apache-2.0
// PushLink: the state of one push to a server: connected or waiting to retry, with a back-off between attempts so a
// server that is down costs a connect per delay, never the stream's time. Counted for /state and /metrics.
#pragma once

#include <string>

#include "base/backoff.h"

namespace overlayd {

class PushLink
{
public:
    explicit PushLink(Backoff backoff = Backoff(Backoff::Duration(500), Backoff::Duration(16000)));

    // The server took the stream: the next failure retries after the shortest delay again.
    void connected();
    struct Retry {
        Backoff::Duration delay; // before the next attempt
        bool newReason;          // a reason unlike the last one: worth a log line (a retry loop logs each once)
    };
    // An attempt failed or a connected push broke.
    Retry failed(const std::string &reason);
    // The next attempt starts (after the delay failed() gave).
    void retrying() { ++reconnects_; }

    bool isConnected() const { return connected_; }
    unsigned reconnects() const { return reconnects_; }
    const std::string &lastError() const { return lastError_; }

private:
    Backoff backoff_;
    bool connected_ = false;
    unsigned reconnects_ = 0;
    std::string lastError_;
};

} // namespace overlayd
