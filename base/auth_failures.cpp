// SPDX-License-Identifier: Apache-2.0
// AuthFailures: per-address windows of refused credentials.
#include "base/auth_failures.h"

#include <algorithm>

namespace overlayd {

AuthFailures::Window &AuthFailures::windowOf(const std::string &address, Clock::time_point now)
{
    if (windows_.size() >= kMaxAuthAddresses && !windows_.count(address)) {
        const auto oldest = std::min_element(windows_.begin(), windows_.end(), [](const auto &a, const auto &b) {
            return a.second.start < b.second.start;
        });
        windows_.erase(oldest);
    }
    Window &window = windows_[address];
    if (now - window.start >= std::chrono::seconds(kAuthWindowSec))
        window = Window{now};
    return window;
}

bool AuthFailures::blocked(const std::string &address, Clock::time_point now)
{
    const auto found = windows_.find(address);
    if (found == windows_.end())
        return false;
    const bool over =
        now - found->second.start < std::chrono::seconds(kAuthWindowSec) && found->second.failures >= kMaxAuthFailures;
    blocked_ += over;
    return over;
}

std::string AuthFailures::failed(const std::string &address, const std::string &what, Clock::time_point now)
{
    ++refused_;
    Window &window = windowOf(address, now);
    ++window.failures;
    if (window.logged && window.failures < kMaxAuthFailures)
        return {};
    if (window.failures > kMaxAuthFailures)
        return {};
    window.logged = true;
    if (window.failures == kMaxAuthFailures)
        return subject_ + ": " + std::to_string(kMaxAuthFailures) + " refused credentials from " + address +
               " within " + std::to_string(kAuthWindowSec) +
               " s: its credentials are not compared until the window ends";
    return subject_ + ": refused a credential from " + address + " (" + what + "); the next line at " +
           std::to_string(kMaxAuthFailures) + " within " + std::to_string(kAuthWindowSec) + " s";
}

} // namespace overlayd
