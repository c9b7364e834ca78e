// Daemon: the event loop's wiring, periodic stats, the watchdog and shutdown (SIGHUP reloads: reload.cpp).
#include "daemon/daemon.h"

#include <csignal>
#include <cstdio>
#include <cstring>

namespace overlayd {

int Daemon::run()
{
    auto loop = EventLoop::create();
    if (!loop || !signals_) {
        logger_.error(cat("event loop: ", !loop ? loop.error().message : "start() did not succeed"));
        return 1;
    }
    loop_ = &*loop;
    loop->setFailureLog(
        [this](const std::string &what) { logger_.error("event loop: a handler failed and was skipped: " + what); });
    (void)loop->add(signals_->fd(), [this] {
        while (const int signal = signals_->read()) {
            if (signal == SIGHUP) {
                reload();
                continue;
            }
            logger_.notice(cat("stopping on ", sigabbrev_np(signal) ? sigabbrev_np(signal) : "signal"));
            requestStop(0);
        }
    });
    (void)loop->add(pacing_->fd(), [this] {
        if (pacing_->consume())
            onFrameReady();
    });
    (void)loop->add(retry_->fd(), [this] { onRetry(); });
    (void)loop->add(noSignalTimer_->fd(), [this] { onNoSignalTick(); });
    (void)loop->add(stats_->fd(), [this] { onStats(); });
    (void)loop->add(watchdog_->fd(), [this] { onWatchdog(); });
    source_->attachLoop(loop_);
    gpio_.attachLoop(loop_);
    http_.attachLoop(loop_);
    textInputs_.attachLoop(loop_);
    pathInputs_.attachLoop(loop_);
    canInputs_.attachLoop(loop_);
    while (state() != State::Finished) {
        gpio_.onState(state()); // outputs follow the state the last turn left
        if (auto status = loop->runOnce(); !status) {
            logger_.error(status.error().message);
            requestStop(1);
        }
    }
    shutdown();
    canInputs_.attachLoop(nullptr);
    pathInputs_.attachLoop(nullptr);
    textInputs_.attachLoop(nullptr);
    http_.attachLoop(nullptr);
    gpio_.attachLoop(nullptr);
    source_->attachLoop(nullptr);
    loop_ = nullptr;
    return exitStatus_;
}

void Daemon::shutdown()
{
    health_.notifier().stopping();
    gpio_.shutdown(); // outputs back to their inactive level
    source_->close();
    pipeline_.closeSinks();
    const PipelineStats stats = pipeline_.takeStats();
    logger_.info(cat("stopped after ", pipeline_.framesIn(), " frames; last period: ", stats.describe()));
    logger_.flush();
}

void Daemon::onStats()
{
    stats_->consume();
    health_.onStats(pipeline_, state() == State::Streaming);
    if (!gpio_.empty())
        logger_.info(cat("gpio: ", gpio_.describe()));
    if (canInputs_.size() > 0)
        logger_.info(cat("input.can: ", canInputs_.describe(CanInputs::Clock::now())));
}

void Daemon::onWatchdog()
{
    watchdog_->consume();
    health_.onWatchdog(state() == State::Streaming, state() == State::Waiting, pipeline_.format(), source_->describe());
}

void Daemon::armStats()
{
    const double interval = config_.daemon.statsIntervalSec;
    if (interval > 0) {
        const auto period = std::chrono::nanoseconds(int64_t(interval * 1e9));
        (void)stats_->arm(period, period);
    } else {
        stats_->disarm();
    }
}

void Daemon::applyLogLevel()
{
    logger_.setLevel(options_.logLevel.value_or(config_.daemon.logLevel));
}

} // namespace overlayd
