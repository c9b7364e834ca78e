// SPDX-License-Identifier: Apache-2.0
// SourceSupervisor: the source's life under `overlayd run`. It opens the stream (openStream), pulls frames while it
// streams (paced by a timer, or woken by the device's fd), and while the source is down feeds the sinks NO SIGNAL
// frames and retries with back-off. A camera that vanishes is waited for, never a reason to exit. A reload that
// changes the source opens the new one first (stage) and switches only when the whole reload is ready (adopt).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/backoff.h"
#include "base/event_loop.h"
#include "base/logger.h"
#include "config/daemon_config.h"
#include "control/run_state.h"
#include "control/scene_control.h"
#include "daemon/health_reporter.h"
#include "daemon/no_signal.h"
#include "daemon/open_stream.h"
#include "daemon/pipeline.h"
#include "daemon/stages.h"
#include "drivers/frame_source.h"

namespace overlayd {

class SourceSupervisor
{
public:
    using State = RunState;
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
    // A reload's new stream, open but not yet running.
    struct Staged {
        OpenedStream stream;
        bool closedRunning = false; // the running source was closed to make way for it (the same device)
    };
    // Reload, first half: opens the new config's source with the candidate scene's overlay. A different device is
    // opened while the running one streams on; one that may be the same device (mayShareDevice) is opened after the
    // running one is closed, and when it fails the running one is opened again as it was. On failure the running
    // stream is as it was (or, if its device will not open again either, waited for as if it had been lost).
    Result<Staged> stage(const DaemonConfig &next, const SceneControl &nextScene);
    // Reload, second half, once the daemon switched its config and scene: the staged stream replaces the running one.
    // The pipeline's sinks are already open for its format.
    void adopt(Staged staged);
    // The reload was refused after stage(): the new stream is closed, the running one re-opened if it was closed.
    void discard(Staged staged);
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
    void startStreaming(std::unique_ptr<FrameSource> source);
    // The running source again, after a staged one that took its device was given up.
    Status reopenRunning();
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
