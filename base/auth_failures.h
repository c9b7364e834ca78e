// SPDX-License-Identifier: Apache-2.0
// AuthFailures: refused credentials per client address, so that guessing is slow (beyond kMaxAuthFailures within
// kAuthWindowSec the server refuses an address without comparing its credential: HTTP answers 429, RTSP 401) and
// the log says who tried without being flooded (one line per address per window, with the count). The HTTP server
// and each RTSP sink keep their own.
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace overlayd {

// Limits (docs/config.md "Limits").
inline constexpr unsigned kMaxAuthFailures = 10;  // refused credentials from one address within the window:
inline constexpr unsigned kAuthWindowSec = 60;    // beyond, its credentials are refused without being compared
inline constexpr size_t kMaxAuthAddresses = 1024; // addresses remembered (the oldest forgotten first)

class AuthFailures
{
public:
    using Clock = std::chrono::steady_clock;

    // `subject` begins each line: "http", "sink[0]: RTSP".
    explicit AuthFailures(std::string subject) : subject_(std::move(subject)) {}

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

    std::string subject_;
    std::map<std::string, Window> windows_;
    uint64_t refused_ = 0, blocked_ = 0;
};

} // namespace overlayd
