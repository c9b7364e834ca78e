// SPDX-License-Identifier: Apache-2.0
// StartupGuard: a thread that polls the stop signals and "start-up is over", and exits the process on the first.
#include "tools/startup_guard.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>

namespace overlayd {

namespace {

Error systemError(const char *what)
{
    return makeError(ErrorCode::Io, std::string(what) + ": " + std::strerror(errno));
}

} // namespace

Result<std::unique_ptr<StartupGuard>> StartupGuard::start(Logger &logger, int stopStatus)
{
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGINT);
    UniqueFd signals(::signalfd(-1, &stop, SFD_NONBLOCK | SFD_CLOEXEC));
    if (!signals.isValid())
        return systemError("signalfd");
    UniqueFd done(::eventfd(0, EFD_CLOEXEC));
    if (!done.isValid())
        return systemError("eventfd");
    return std::unique_ptr<StartupGuard>(new StartupGuard(logger, stopStatus, std::move(signals), std::move(done)));
}

StartupGuard::StartupGuard(Logger &logger, int stopStatus, UniqueFd signals, UniqueFd done)
    : logger_(logger), stopStatus_(stopStatus), signals_(std::move(signals)), done_(std::move(done)),
      thread_(&StartupGuard::threadMain, this)
{}

StartupGuard::~StartupGuard()
{
    const uint64_t one = 1;
    if (::write(done_.get(), &one, sizeof(one)) != sizeof(one))
        logger_.error(cat("start-up guard: eventfd write: ", std::strerror(errno)));
    thread_.join();
}

void StartupGuard::threadMain()
{
    pollfd fds[2] = {{done_.get(), POLLIN, 0}, {signals_.get(), POLLIN, 0}};
    signalfd_siginfo info{};
    for (;;) {
        if (::poll(fds, 2, -1) < 0 && errno != EINTR)
            return; // cannot happen with valid fds; the loop's signalfd still sees the signal after start-up
        if (fds[0].revents)
            return;
        if (fds[1].revents && ::read(signals_.get(), &info, sizeof(info)) == sizeof(info))
            break;
    }
    // Nothing has been streamed yet, so there is nothing to flush or close in order: whatever start-up is blocked
    // in (on another thread) is abandoned and the kernel closes its files.
    const char *name = sigabbrev_np(int(info.ssi_signo));
    logger_.notice(cat("stopping on ", name ? name : "signal", " during start-up"));
    logger_.flush();
    ::_exit(stopStatus_);
}

} // namespace overlayd
