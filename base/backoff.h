// SPDX-License-Identifier: Apache-2.0
// Backoff: the delays between attempts to reach something lost (a source, a push server), doubling from a floor
// to a ceiling.
#pragma once

#include <chrono>

namespace overlayd {

class Backoff
{
public:
    using Duration = std::chrono::milliseconds;

    explicit Backoff(Duration first = Duration(500), Duration ceiling = Duration(8000));

    // The delay before the next attempt; each call doubles the following one, up to the ceiling.
    Duration next();
    // The delay next() will return, without advancing (for "retry in 4 s" messages after scheduling).
    Duration peek() const { return current_; }
    // A successful attempt: start again from the floor.
    void reset();
    unsigned attempts() const { return attempts_; }

private:
    Duration first_, ceiling_, current_;
    unsigned attempts_ = 0;
};

} // namespace overlayd
