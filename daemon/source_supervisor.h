// SourceSupervisor: the source's life under `overlayd run`. It opens the stream (openStream), pulls frames while it
// streams (paced by a timer, or woken by the device's fd), and while the source is down feeds the sinks NO SIGNAL
// frames and retries with back-off. A camera that vanishes is waited for, never a reason to exit.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/logger.h"
#include "config/daemon_config.h"
#include "daemon/backoff.h"
#include "daemon/event_loop.h"
#include "daemon/health_reporter.h"
#include "daemon/no_signal.h"
#include "daemon/pipeline.h"
#include "daemon/scene_control.h"
#include "daemon/stages.h"
#include "drivers/frame_source.h"

namespace overlayd {

class SourceSupervisor
{
public:
    enum class State { Idle, Streaming, Waiting, Finished };
    // The loop's timers the supervisor arms (owned by the daemon, created before any thread starts).
    struct Timers {
        Timer &pacing, &retry, &noSignal;
    };
    // Called after each source frame went through the pipeline (the frame limit lives with the caller), and when the
    // stream must end (0: the source ended; 1: it failed for good).
    using FrameHook = std::function<void()>;
    using StopHook = std::function<void(int exitStatus)>;

    SourceSupervisor(Logger &logger, const DaemonConfig &config, SourceFactory makeSource, Pipeline &pipeline,
                     SceneControl &scene, HealthReporter &health, Timers timers, FrameHook onFrame, StopHook stop);
    ~SourceSupervisor() { close(); }

    // Opens the source; the first time (Idle) a sink that cannot open is fatal. A source that is absent
    // (retryable) is then waited for with enterWaiting().
    Status open();
    void close();
    // Closes and opens again (a reload changed what the source is built from); a failure waits for it.
    void reopen();
    bool isRetryable(const Error &error) const;
    void enterWaiting(const Error &error);
    // The loop is running: the source's fd (if any) is watched in it.
    void attachLoop(EventLoop *loop);
    void finish() { state_ = State::Finished; }

    // Loop handlers.
    void onFrameReady();
    void onRetry();
    // While waiting: the NO SIGNAL frame's pacing; while streaming: the stall timer ran out.
    void onNoSignalTick();

    State state() const { return state_; }
    const std::string &waitReason() const { return waitReason_; }
    std::chrono::milliseconds nextRetryDelay() const { return backoff_.peek(); }
    std::string describe() const { return source_ ? source_->describe() : "the source"; }

private:
    void watchSource();
    void scheduleRetry();
    void handleSourceError(const Error &error);
    void replaceNoSignal(const StreamFormat &format);
    StreamFormat configuredFormat() const;
    double pacingFps() const;
    // A camera that stops delivering without an error (a wedged driver, a camera libcamera lost track of) is torn
    // down after its no_signal_timeout; files and synthetic sources have none.
    std::optional<std::chrono::nanoseconds> stallTimeout() const;
    void armStallTimer();
    std::chrono::nanoseconds pacingPeriod() const;

    Logger &logger_;
    const DaemonConfig &config_; // the daemon's; a reload replaces it in place
    SourceFactory makeSource_;
    Pipeline &pipeline_;
    SceneControl &scene_;
    HealthReporter &health_;
    Timers timers_;
    FrameHook onFrame_;
    StopHook stop_;

    State state_ = State::Idle;
    std::unique_ptr<FrameSource> source_;
    EventLoop *loop_ = nullptr; // set while the loop runs
    int watchedSourceFd_ = -1;
    Backoff backoff_;
    std::string waitReason_;
    std::optional<NoSignalFrame> noSignal_;
    uint64_t noSignalSequence_ = 0;
};

} // namespace overlayd
