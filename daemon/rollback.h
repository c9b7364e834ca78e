// SPDX-License-Identifier: Apache-2.0
// Rollback: what a change made of several steps has done so far, undone in reverse order unless it is committed (a
// reload's GPIO lines, file watches, HTTP server and staged source, when a later step refuses the reload).
#pragma once

#include <functional>
#include <vector>

namespace overlayd {

class Rollback
{
public:
    Rollback() = default;
    Rollback(const Rollback &) = delete;
    Rollback &operator=(const Rollback &) = delete;
    ~Rollback()
    {
        for (auto undo = undo_.rbegin(); undo != undo_.rend(); ++undo)
            (*undo)();
    }

    // What puts back the step just taken.
    void add(std::function<void()> undo) { undo_.push_back(std::move(undo)); }
    // Every step stays.
    void commit() { undo_.clear(); }

private:
    std::vector<std::function<void()>> undo_;
};

} // namespace overlayd
