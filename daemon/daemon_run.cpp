// Daemon: the event loop's wiring, periodic stats, the watchdog, STATUS= lines and shutdown.
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
    if (source_ && source_->eventFd() >= 0) {
        watchedSourceFd_ = source_->eventFd();
        (void)loop->add(watchedSourceFd_, [this] { onFrameReady(); });
    }
    while (state_ != State::Finished) {
        if (auto status = loop->runOnce(); !status) {
            logger_.error(status.error().message);
            requestStop(1);
        }
    }
    shutdown();
    loop_ = nullptr;
    return exitStatus_;
}

void Daemon::shutdown()
{
    notifier_.stopping();
    if (loop_ && watchedSourceFd_ >= 0)
        loop_->remove(watchedSourceFd_);
    watchedSourceFd_ = -1;
    closeSource();
    pipeline_.closeSinks();
    const PipelineStats stats = pipeline_.takeStats();
    logger_.info(cat("stopped after ", pipeline_.framesIn(), " frames; last period: ", stats.describe()));
    logger_.flush();
}

void Daemon::onStats()
{
    stats_->consume();
    const PipelineStats stats = pipeline_.takeStats();
    totalDrops_ = stats.totalDrops;
    logger_.info(cat("stats: ", stats.describe()));
    updateStatus();
}

void Daemon::onWatchdog()
{
    watchdog_->consume();
    // A wedged source must make systemd restart us: pet only when frames flowed since the last pet, or while a
    // deliberate reconnect is in progress (the NO SIGNAL frames prove the loop itself is alive).
    if (framesSincePet_ > 0 || state_ == State::Waiting)
        notifier_.watchdog();
    reportStall();
    framesSincePet_ = 0;
}

// A stalled stream stops the watchdog; STATUS= says why, so `systemctl status` does not keep claiming "streaming".
void Daemon::reportStall()
{
    const bool stalled = state_ == State::Streaming && framesSincePet_ == 0;
    if (!stalled) {
        if (idleWatchdogTicks_ > 0)
            updateStatus();
        idleWatchdogTicks_ = 0;
        return;
    }
    ++idleWatchdogTicks_;
    const auto interval = notifier_.watchdogInterval().value_or(std::chrono::microseconds(0));
    const double idleSec = double(idleWatchdogTicks_) * double(interval.count()) * 1e-6;
    char line[160];
    std::snprintf(line, sizeof(line), "stalled: no frame from %s for %.1f s",
                  source_ ? source_->describe().c_str() : "the source", idleSec);
    notifier_.status(line);
}

void Daemon::updateStatus()
{
    if (state_ == State::Streaming)
        notifier_.status(cat("streaming ", pipeline_.format().describe(), ", ", totalDrops_, " drops"));
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

bool Daemon::reload()
{
    notifier_.reloading();
    logger_.notice(cat("reloading ", options_.configPath));
    const auto reject = [this](const std::string &why) {
        logger_.error(cat("reload failed, keeping the previous config: ", why));
        notifier_.status(cat("reload failed, kept the previous config: ", why));
        notifier_.ready();
        return false;
    };
    std::vector<ConfigProblem> problems;
    auto loaded = loader_(options_.configPath, problems);
    if (!loaded) {
        for (const ConfigProblem &problem : problems)
            logger_.error(problem.format());
        return reject(cat(problems.size(), " problem(s) in ", options_.configPath));
    }
    DaemonConfig next = std::move(*loaded);
    const bool sourceChanged = !sameSourceOptions(config_.source, next.source) || sceneCameraChanged(config_, next) ||
                               wantsZeroCopy(config_) != wantsZeroCopy(next);
    const bool sinksChanged = !sameSinkOptions(config_.sinks, next.sinks);

    // Everything that can fail is built before anything is switched; the scene goes through the same SceneControl
    // as every live change (a re-opened source builds its overlay from it when it starts).
    Status sinksBuilt = Ok{};
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    if (sinksChanged) {
        sinks = buildSinks(next, sinksBuilt);
        if (!sinksBuilt)
            return reject(sinksBuilt.error().message);
    }
    std::unique_ptr<OverlayRenderer> renderer;
    if (sourceChanged || state_ != State::Streaming)
        scene_.detach(); // nothing to rebuild now: the next stream is built from the new scene
    if (auto applied = scene_.apply(SceneReplacement{next.scene, next.camera}, &renderer); !applied)
        return reject(applied.error().message);

    // The switch, between two frames (we are in the loop, not in the middle of one).
    if (sinksChanged) {
        pipeline_.setSinks(std::move(sinks));
        if (pipeline_.format().format)
            (void)pipeline_.openSinks(pipeline_.format());
    }
    config_ = std::move(next);
    applyLogLevel();
    armStats();
    if (sourceChanged) {
        closeSource();
        if (auto opened = openSource(); !opened)
            enterWaiting(opened.error());
    } else if (state_ == State::Streaming) {
        pipeline_.setRenderer(std::move(renderer));
        scene_.attach(pipeline_.renderer(), pipeline_.format());
    }
    logger_.notice(cat("reloaded ", options_.configPath, sourceChanged ? " (source re-opened)" : "",
                       sinksChanged ? " (sinks re-opened)" : ""));
    updateStatus();
    notifier_.ready();
    return true;
}

} // namespace overlayd
