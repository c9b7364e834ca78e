// SPDX-License-Identifier: Apache-2.0
// The event loop's kernel objects: epoll, timerfd and signalfd, each owned by a UniqueFd.
#include "base/event_loop.h"

#include <cerrno>
#include <cstring>
#include <exception>
#include <string>

#include <sys/epoll.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

namespace overlayd {

namespace {

Error systemError(const char *what)
{
    return makeError(ErrorCode::Io, std::string(what) + ": " + std::strerror(errno));
}

timespec toTimespec(std::chrono::nanoseconds duration)
{
    const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(duration);
    return timespec{time_t(seconds.count()), long((duration - seconds).count())};
}

} // namespace

Result<Timer> Timer::create()
{
    const int fd = ::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    if (fd < 0)
        return systemError("timerfd_create");
    return Timer(UniqueFd(fd));
}

Status Timer::arm(std::chrono::nanoseconds first, std::chrono::nanoseconds period)
{
    // A zero it_value would disarm the timer: fire as soon as possible instead.
    itimerspec spec{toTimespec(period), toTimespec(std::max(first, std::chrono::nanoseconds(1)))};
    if (::timerfd_settime(fd_.get(), 0, &spec, nullptr) < 0)
        return systemError("timerfd_settime");
    return Ok{};
}

void Timer::disarm()
{
    itimerspec spec{};
    ::timerfd_settime(fd_.get(), 0, &spec, nullptr);
}

uint64_t Timer::consume()
{
    uint64_t expirations = 0;
    if (::read(fd_.get(), &expirations, sizeof(expirations)) != sizeof(expirations))
        return 0;
    return expirations;
}

Result<SignalReader> SignalReader::create()
{
    sigset_t signals;
    sigemptyset(&signals);
    for (int signal : {SIGTERM, SIGINT, SIGHUP})
        sigaddset(&signals, signal);
    // pthread_sigmask before any worker thread exists: the threads inherit the mask, so only the signalfd sees them.
    if (::pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0)
        return systemError("pthread_sigmask");
    const int fd = ::signalfd(-1, &signals, SFD_NONBLOCK | SFD_CLOEXEC);
    if (fd < 0)
        return systemError("signalfd");
    return SignalReader(UniqueFd(fd));
}

int SignalReader::read()
{
    signalfd_siginfo info{};
    if (::read(fd_.get(), &info, sizeof(info)) != sizeof(info))
        return 0;
    return int(info.ssi_signo);
}

Result<EventLoop> EventLoop::create()
{
    const int fd = ::epoll_create1(EPOLL_CLOEXEC);
    if (fd < 0)
        return systemError("epoll_create1");
    return EventLoop(UniqueFd(fd));
}

Status EventLoop::add(int fd, Handler handler)
{
    epoll_event event{};
    event.events = EPOLLIN;
    event.data.fd = fd;
    if (::epoll_ctl(epoll_.get(), EPOLL_CTL_ADD, fd, &event) < 0)
        return systemError("epoll_ctl(ADD)");
    handlers_[fd] = std::move(handler);
    return Ok{};
}

void EventLoop::remove(int fd)
{
    ::epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, fd, nullptr);
    handlers_.erase(fd);
}

Status EventLoop::runOnce(int timeoutMs)
{
    epoll_event events[16];
    const int count = ::epoll_wait(epoll_.get(), events, 16, timeoutMs);
    if (count < 0)
        return errno == EINTR ? Status(Ok{}) : Status(systemError("epoll_wait"));
    for (int i = 0; i < count && !stopped_; ++i) {
        // A handler may have removed this fd (a source torn down): look it up each time.
        auto found = handlers_.find(events[i].data.fd);
        if (found == handlers_.end())
            continue;
        Handler handler = found->second; // a copy: the handler may remove itself
        dispatch(handler);
    }
    return Ok{};
}

void EventLoop::dispatch(const Handler &handler)
{
    try {
        handler();
    } catch (const std::exception &error) {
        reportFailure(error.what());
    } catch (...) {
        reportFailure("an exception that is not a std::exception");
    }
}

void EventLoop::reportFailure(const char *what) noexcept
{
    try {
        if (failureLog_)
            failureLog_(what);
    } catch (...) {
        // Out of memory even for the log line: the loop goes on regardless.
    }
}

Status EventLoop::run()
{
    while (!stopped_) {
        if (auto status = runOnce(); !status)
            return status;
    }
    return Ok{};
}

} // namespace overlayd
