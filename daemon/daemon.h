// SPDX-License-Identifier: Apache-2.0
// Daemon: `overlayd run`. It loads the config, builds the sinks, and wires one event loop to the three parts that do
// the work: the SourceSupervisor (the source, NO SIGNAL and reconnects), the HealthReporter (readiness, watchdog,
// STATUS=, stats) and SceneControl (every change to the running scene, SIGHUP reloads among them).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/event_loop.h"
#include "base/logger.h"
#include "config/daemon_config.h"
#include "control/can_inputs.h"
#include "control/daemon_status.h"
#include "control/gpio_control.h"
#include "control/http_front.h"
#include "control/path_inputs.h"
#include "control/scene_control.h"
#include "control/text_inputs.h"
#include "daemon/encoded_stream_report.h"
#include "daemon/health_reporter.h"
#include "daemon/pipeline.h"
#include "daemon/source_supervisor.h"
#include "daemon/stages.h"
#include "daemon/systemd_notify.h"

namespace overlayd {

using ConfigLoader = std::function<Result<DaemonConfig>(const std::string &path, std::vector<ConfigProblem> &)>;

struct DaemonOptions {
    std::string configPath;
    std::optional<LogLevel> logLevel; // --log-level wins over the config's daemon.log_level
    uint64_t maxFrames = 0;           // stop cleanly after this many source frames (0: until signalled)
};

class Daemon final : public DaemonStatus
{
public:
    Daemon(Logger &logger, SystemdNotifier &notifier, StageFactories factories, ConfigLoader loader,
           DaemonOptions options);
    ~Daemon();

    // Loads the config and opens the pipeline. A source that is absent (DeviceLost, NotFound) is waited for; any
    // other failure (a bad config, a sink that cannot open) is logged and returned: the caller exits non-zero.
    Status start();
    // The event loop until SIGTERM/SIGINT, the end of the source, the frame limit or a fatal error; returns the
    // process exit status.
    int run();

    // The event handlers run() wires to its fds; public so that tests drive them without a loop or signals.
    void onFrameReady() { source_->onFrameReady(); }
    void onRetry() { source_->onRetry(); }
    void onNoSignalTick() { source_->onNoSignalTick(); }
    void onStats();
    void onWatchdog();
    // A transaction: the whole new config is built and opened (source, overlay, GPIO lines, inputs, HTTP server,
    // sinks) before anything is switched; false, with the old config still running as it was, when any part fails.
    bool reload();
    void requestStop(int exitStatus);

    State state() const override { return source_ ? source_->state() : State::Idle; }
    const DaemonConfig &config() const override { return config_; }
    const Pipeline &pipeline() const { return pipeline_; }
    const StreamFormat &streamFormat() const override { return pipeline_.format(); }
    uint64_t framesIn() const override { return pipeline_.framesIn(); }
    std::vector<const StatusReporter *> reporters() const override;
    std::shared_ptr<EncodedStream> encodedStream() const override { return stream_; }
    // The one path into the running scene (reload uses it too); call on the loop thread.
    SceneControl &scene() { return scene_; }
    const GpioControl &gpio() const { return gpio_; }
    GpioControl &gpio() { return gpio_; }
    const TextInputs &textInputs() const { return textInputs_; }
    TextInputs &textInputs() { return textInputs_; }
    const PathInputs &pathInputs() const { return pathInputs_; }
    PathInputs &pathInputs() { return pathInputs_; }
    const CanInputs &canInputs() const { return canInputs_; }
    CanInputs &canInputs() { return canInputs_; }
    const std::string &waitReason() const { return source_->waitReason(); }
    std::chrono::milliseconds nextRetryDelay() const { return source_->nextRetryDelay(); }
    int exitStatus() const { return exitStatus_; }

private:
    Status setUp();
    Status createTimers();
    // Loads the config file; every problem is logged (one line each, at file:line:column) and returned.
    Result<DaemonConfig> loadConfig(std::vector<ConfigProblem> &problems);
    struct ReopenedParts {
        bool source = false, sinks = false;
    };
    // Everything a reload does once the new file has loaded; an error: nothing was switched.
    Result<ReopenedParts> switchConfig(DaemonConfig next);
    // The switch itself, which cannot fail: between two frames, with every new part already open.
    void commitConfig(DaemonConfig next, SceneControl scene, std::optional<SourceSupervisor::Staged> stream,
                      std::unique_ptr<OverlayRenderer> renderer);
    void onFrameDelivered();
    void armStats();
    // The sinks of a config; with keepStream, without the encoded outputs' sink: the running one goes on (its
    // [encoder] and encoded sinks are the config's).
    std::vector<std::unique_ptr<SinkWorker>> buildSinks(const DaemonConfig &config, Status &status,
                                                        bool keepStream = false);
    void applyLogLevel();
    uint64_t sinkFailures() const;
    void shutdown();

    Logger &logger_;
    StageFactories factories_;
    ConfigLoader loader_;
    DaemonOptions options_;

    DaemonConfig config_;
    int exitStatus_ = 0;
    Pipeline pipeline_;
    SceneControl scene_;
    HealthReporter health_;
    GpioControl gpio_;      // after scene_, whose layers it switches
    TextInputs textInputs_; // after scene_, whose slots it feeds
    PathInputs pathInputs_; // after scene_, whose polylines and markers it feeds
    CanInputs canInputs_;   // after scene_, whose guide lines and slots it feeds
    // The encoded outputs the running sinks feed, and those buildSinks() made for sinks not yet switched in.
    std::shared_ptr<EncodedStream> stream_, builtStream_;
    EncodedStreamReport streamReport_{stream_}; // reports whichever encoded stream runs, or nothing
    HttpFront http_;                            // after everything its API reads

    EventLoop *loop_ = nullptr;           // set while run() is running
    std::optional<SignalReader> signals_; // created before any sink thread, so that every thread blocks them
    std::optional<Timer> pacing_, retry_, noSignalTimer_, stats_, watchdog_;
    std::unique_ptr<SourceSupervisor> source_; // after the timers it arms
    bool configProblemsLogged_ = false;
};

} // namespace overlayd
