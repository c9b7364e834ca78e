// SPDX-License-Identifier: Apache-2.0
// The daemon's event loop: epoll over owned file descriptors, with timerfd and signalfd wrappers.
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

// A CLOCK_MONOTONIC timerfd. Not armed until arm() is called.
class Timer
{
public:
    static Result<Timer> create();

    // First expiry after `first`, then every `period` (zero: one-shot).
    Status arm(std::chrono::nanoseconds first, std::chrono::nanoseconds period = {});
    void disarm();
    // Reads and returns the number of expirations since the last read (0 if none: spurious wake-up).
    uint64_t consume();
    int fd() const { return fd_.get(); }

private:
    explicit Timer(UniqueFd fd) : fd_(std::move(fd)) {}
    UniqueFd fd_;
};

// SIGTERM, SIGINT and SIGHUP through a signalfd: they are blocked for the whole process (before any thread starts)
// and read in the loop, so nothing runs in signal context.
class SignalReader
{
public:
    static Result<SignalReader> create();
    // The next pending signal number, or 0 when none is pending.
    int read();
    int fd() const { return fd_.get(); }

private:
    explicit SignalReader(UniqueFd fd) : fd_(std::move(fd)) {}
    UniqueFd fd_;
};

class EventLoop
{
public:
    using Handler = std::function<void()>;

    static Result<EventLoop> create();

    // Calls handler whenever fd is readable. The fd stays owned by the caller and must be removed before closing.
    Status add(int fd, Handler handler);
    void remove(int fd);
    // Waits for events up to timeout (negative: forever) and runs their handlers.
    Status runOnce(int timeoutMs = -1);
    // Runs until stop() is called from a handler.
    Status run();
    // Where a handler's exception is reported: it is caught in the loop (a bug in one callback must not end the
    // daemon), the loop goes on with the next event.
    void setFailureLog(std::function<void(const std::string &what)> log) { failureLog_ = std::move(log); }
    void stop() { stopped_ = true; }
    bool stopped() const { return stopped_; }

private:
    explicit EventLoop(UniqueFd epoll) : epoll_(std::move(epoll)) {}
    void dispatch(const Handler &handler);
    void reportFailure(const char *what) noexcept;
    UniqueFd epoll_;
    std::map<int, Handler> handlers_;
    std::function<void(const std::string &)> failureLog_;
    bool stopped_ = false;
};

} // namespace overlayd
