// Daemon: the event loop's wiring, SIGHUP reloads, periodic stats, the watchdog and shutdown.
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

bool Daemon::reload()
{
    SystemdNotifier &notifier = health_.notifier();
    notifier.reloading();
    logger_.notice(cat("reloading ", options_.configPath));
    const auto reject = [this, &notifier](const std::string &why) {
        logger_.error(cat("reload failed, keeping the previous config: ", why));
        notifier.status(cat("reload failed, kept the previous config: ", why));
        notifier.ready();
        return false;
    };
    size_t problems = 0;
    auto loaded = loadConfig(problems);
    if (!loaded)
        return reject(cat(problems, " problem(s) in ", options_.configPath));
    DaemonConfig next = std::move(*loaded);
    // Whole option structs are compared: a field added to them later re-opens what it belongs to.
    const bool sourceChanged = config_.source != next.source || sceneCameraChanged(config_, next) ||
                               wantsZeroCopy(config_) != wantsZeroCopy(next);
    const bool sinksChanged = config_.sinks != next.sinks || config_.http.enabled != next.http.enabled;

    // Everything that can fail is built before anything is switched; the scene goes through the same SceneControl
    // as every live change (a re-opened source builds its overlay from it when it starts).
    Status sinksBuilt = Ok{};
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    if (sinksChanged) {
        sinks = buildSinks(next, sinksBuilt);
        if (!sinksBuilt)
            return reject(sinksBuilt.error().message);
    }
    // GPIO lines next: a line that cannot be requested refuses the reload with every old line still held.
    const bool gpioChanged = config_.gpio != next.gpio;
    if (gpioChanged)
        if (auto lines = gpio_.configure(next.gpio); !lines)
            return reject(lines.error().message);
    // File inputs next (a folder that cannot be watched refuses the reload).
    const bool inputsChanged = config_.inputs != next.inputs;
    bool textWatched = false, pathsWatched = false, httpServed = false;
    // A refusal after some part was switched: the old lines, watches and server again.
    const auto rollBack = [&](const std::string &why) {
        if (gpioChanged)
            (void)gpio_.configure(config_.gpio);
        if (textWatched)
            (void)textInputs_.configure(config_.inputs.text);
        if (pathsWatched)
            (void)pathInputs_.configure(config_.inputs.paths);
        if (httpServed)
            (void)http_.configure(config_.http);
        return reject(why);
    };
    if (inputsChanged) {
        if (auto watched = textInputs_.configure(next.inputs.text); !watched)
            return rollBack(watched.error().message);
        textWatched = true;
        if (auto watched = pathInputs_.configure(next.inputs.paths); !watched)
            return rollBack(watched.error().message);
        pathsWatched = true;
    }
    // The HTTP server next (a port already taken refuses the reload; the old server keeps serving).
    const bool httpChanged = config_.http != next.http;
    if (httpChanged) {
        if (auto served = http_.configure(next.http); !served)
            return rollBack(served.error().message);
        httpServed = true;
    }
    std::unique_ptr<OverlayRenderer> renderer;
    if (sourceChanged || state() != State::Streaming)
        scene_.detach(); // nothing to rebuild now: the next stream is built from the new scene
    if (auto applied = scene_.apply(SceneReplacement{next.scene, next.camera}, &renderer); !applied)
        return rollBack(applied.error().message);

    // The switch, between two frames (we are in the loop, not in the middle of one).
    if (sinksChanged) {
        pipeline_.setSinks(std::move(sinks));
        if (pipeline_.format().format)
            (void)pipeline_.openSinks(pipeline_.format());
    }
    config_ = std::move(next);
    if (gpioChanged)
        gpio_.applyLayers(); // the new rules, on the new scene's layers
    textInputs_.showAll();   // the files' lines in the new scene's slots
    pathInputs_.showAll();   // and their points in its polylines and markers
    if (inputsChanged)       // CAN inputs cannot refuse a reload: an interface that is not there is retried
        canInputs_.configure(config_.inputs.can);
    else
        canInputs_.showAll(); // the signals' values on the new scene's guide lines and slots
    applyLogLevel();
    armStats();
    if (sourceChanged) {
        source_->reopen();
    } else if (state() == State::Streaming) {
        pipeline_.setRenderer(std::move(renderer));
        scene_.attach(pipeline_.renderer(), pipeline_.format());
    }
    logger_.notice(cat("reloaded ", options_.configPath, sourceChanged ? " (source re-opened)" : "",
                       sinksChanged ? " (sinks re-opened)" : ""));
    if (state() == State::Streaming)
        health_.streaming(pipeline_.format());
    notifier.ready();
    return true;
}

} // namespace overlayd
