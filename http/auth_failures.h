// SPDX-License-Identifier: Apache-2.0
// AuthFailures: refused credentials per client address, so that guessing is slow (beyond kMaxAuthFailures within
// kAuthWindowSec an address gets 429 without its credential being compared) and the log says who tried without
// being flooded (one line per address per window, with the count).
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace overlayd::http {

class AuthFailures
{
public:
    using Clock = std::chrono::steady_clock;

    // Whether the address has used up its attempts for now.
    bool blocked(const std::string &address, Clock::time_point now);
    // A refused credential; returns the line to log (empty: already logged in this window).
    std::string failed(const std::string &address, const std::string &what, Clock::time_point now);
    uint64_t refused() const { return refused_; }
    uint64_t blockedCount() const { return blocked_; }

private:
    struct Window {
        Clock::time_point start;
        unsigned failures = 0;
        bool logged = false;
    };
    Window &windowOf(const std::string &address, Clock::time_point now);

    std::map<std::string, Window> windows_;
    uint64_t refused_ = 0, blocked_ = 0;
};

} // namespace overlayd::http
