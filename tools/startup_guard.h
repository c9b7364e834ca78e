// SPDX-License-Identifier: Apache-2.0
// StartupGuard: SIGTERM and SIGINT while `overlayd run` starts. Start-up may block where no event loop waits yet
// (a calibration file on a slow mount, a config path that is a FIFO, a device that does not answer), so a thread of
// its own waits on a signalfd for the stop signals and ends the process with the stop's exit status and a log
// line; a stop never
// waits for start-up to finish. SIGHUP is left pending for the loop.
#pragma once

#include <memory>
#include <thread>

#include "base/logger.h"
#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

class StartupGuard
{
public:
    // The stop signals must already be blocked (daemon/early_signals.cpp), so that the thread inherits the mask.
    static Result<std::unique_ptr<StartupGuard>> start(Logger &logger, int stopStatus);
    // Start-up is over: the thread ends and a stop signal that arrives from now on is the loop's.
    ~StartupGuard();
    StartupGuard(const StartupGuard &) = delete;
    StartupGuard &operator=(const StartupGuard &) = delete;

private:
    StartupGuard(Logger &logger, int stopStatus, UniqueFd signals, UniqueFd done);
    void threadMain();

    Logger &logger_;
    int stopStatus_;
    UniqueFd signals_; // a signalfd for SIGTERM and SIGINT only
    UniqueFd done_;    // an eventfd the destructor writes
    std::thread thread_;
};

} // namespace overlayd
