// Daemon: `overlayd run`. One event loop drives the source (paced by a timer, or woken by its fd), the NO SIGNAL
// frames and reconnect back-off while it is down, SIGHUP reloads, periodic stats and the systemd watchdog.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/logger.h"
#include "config/daemon_config.h"
#include "daemon/backoff.h"
#include "daemon/event_loop.h"
#include "daemon/no_signal.h"
#include "daemon/pipeline.h"
#include "daemon/scene_control.h"
#include "daemon/stages.h"
#include "daemon/systemd_notify.h"

namespace overlayd {

using ConfigLoader = std::function<Result<DaemonConfig>(const std::string &path, std::vector<ConfigProblem> &)>;

struct DaemonOptions {
    std::string configPath;
    std::optional<LogLevel> logLevel; // --log-level wins over the config's daemon.log_level
    uint64_t maxFrames = 0;           // stop cleanly after this many source frames (0: until signalled)
};

class Daemon
{
public:
    enum class State { Idle, Streaming, Waiting, Finished };

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
    void onFrameReady();
    void onRetry();
    void onNoSignalTick();
    void onStats();
    void onWatchdog();
    // Validates the new file completely before switching; false (old config kept) when anything is wrong.
    bool reload();
    void requestStop(int exitStatus);

    State state() const { return state_; }
    const DaemonConfig &config() const { return config_; }
    const Pipeline &pipeline() const { return pipeline_; }
    // The one path into the running scene (reload uses it too); call on the loop thread.
    SceneControl &scene() { return scene_; }
    const std::string &waitReason() const { return waitReason_; }
    std::chrono::milliseconds nextRetryDelay() const { return backoff_.peek(); }
    int exitStatus() const { return exitStatus_; }

private:
    Status setUp();
    static std::chrono::nanoseconds framePeriod(double fps);
    Status openSource();
    void closeSource();
    void enterWaiting(const Error &error);
    void scheduleRetry();
    void handleSourceError(const Error &error);
    bool isRetryable(const Error &error) const;
    StreamFormat configuredFormat() const;
    double pacingFps() const;
    void armStats();
    void updateStatus();
    void reportStall();
    std::vector<std::unique_ptr<SinkWorker>> buildSinks(const DaemonConfig &config, Status &status);
    void applyLogLevel();
    void shutdown();

    Logger &logger_;
    SystemdNotifier &notifier_;
    StageFactories factories_;
    ConfigLoader loader_;
    DaemonOptions options_;

    DaemonConfig config_;
    State state_ = State::Idle;
    int exitStatus_ = 0;
    std::unique_ptr<FrameSource> source_;
    Pipeline pipeline_;
    SceneControl scene_;

    EventLoop *loop_ = nullptr; // set while run() is running
    int watchedSourceFd_ = -1;
    std::optional<SignalReader> signals_; // created before any sink thread, so that every thread blocks them
    std::optional<Timer> pacing_, retry_, noSignalTimer_, stats_, watchdog_;

    Backoff backoff_;
    std::string waitReason_;
    std::optional<NoSignalFrame> noSignal_;
    uint64_t noSignalSequence_ = 0;
    uint64_t framesSincePet_ = 0;
    unsigned idleWatchdogTicks_ = 0; // watchdog ticks in a row without a frame while streaming (for STATUS=)
    bool readySent_ = false;
    bool configProblemsLogged_ = false;
    uint64_t totalDrops_ = 0;
};

} // namespace overlayd
