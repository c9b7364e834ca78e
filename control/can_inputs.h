// SPDX-License-Identifier: Apache-2.0
// CanInputs: [[input.can]] at run time. Each signal's frames arrive on a raw CAN socket in the event loop; a valid
// value drives its target (the guide lines' steering, or a text slot) through SceneControl. A value that is out of
// range, or older than the input's timeout, is never shown as if it were true: the target shows "unknown" instead.
// An interface that is missing or goes down is retried every second, never fatal.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "base/event_loop.h"
#include "base/logger.h"
#include "control/scene_control.h"
#include "control/status_reporter.h"
#include "inputs/can_socket.h"
#include "inputs/input_health.h"
#include "inputs/input_options.h"

namespace overlayd {

class CanInputs final : public StatusReporter
{
public:
    using Clock = std::chrono::steady_clock;
    // At most this many frames per input per loop turn: a flooded bus cannot starve the camera.
    static constexpr int kMaxFramesPerWake = 64;
    static constexpr std::chrono::milliseconds kTick{50}, kRetry{1000};

    CanInputs(Logger &logger, SceneControl &scene) : logger_(logger), scene_(scene) {}

    // Takes the inputs of a (re)loaded config; an input identical to one already running keeps its socket and
    // its value. Opening sockets happens on the next tick (never fails the config).
    void configure(const std::vector<CanInputOptions> &options);
    // Shows every input's current state on its target again (a new scene was loaded).
    void showAll();
    // Adds the sockets and the tick timer to the loop (null: removes them).
    void attachLoop(EventLoop *loop);

    // A frame as its socket delivered it; a tick ages values and retries sockets. Public for tests.
    void onFrame(size_t input, const CanFrame &frame, Clock::time_point now);
    void tick(Clock::time_point now);

    enum class State { NoData, Ok, Stale, OutOfRange };
    struct Reading {
        State state = State::NoData;
        double value = 0.0;         // the last decoded value (also when out of range)
        Clock::time_point updated;  // when the last valid frame came (the timeout counts from it)
        Clock::time_point received; // when `value` came (valid or out of range)
        uint64_t frames = 0, malformed = 0, outOfRange = 0;
        bool connected = false;
        std::string error; // why the socket is not open
    };
    size_t size() const { return inputs_.size(); }
    const CanInputOptions &options(size_t input) const { return inputs_[input].options; }
    const Reading &reading(size_t input) const { return inputs_[input].reading; }
    static const char *stateName(State state);
    // Each input's health: following while its socket is open, waiting while the interface is missing or down.
    std::vector<InputHealth> health() const;
    // Its entries in /state and its samples in /metrics.
    void report(StatusReport &report) const override;
    // "steering=40.0 deg ok, ..." for the stats log line.
    std::string describe(Clock::time_point now) const;

private:
    struct Input {
        CanInputOptions options;
        std::optional<CanSocket> socket;
        Reading reading;
        Clock::time_point nextOpen;
        std::optional<double> shown; // what the target shows (nullopt: unknown); unset before the first show
        bool everShown = false;
        InputHealth health;
    };
    void open(size_t input, Clock::time_point now);
    void close(size_t input, const std::string &why, Clock::time_point now);
    void readAll(size_t input);
    void show(size_t input, bool force);
    void wire(size_t input, bool add);

    Logger &logger_;
    SceneControl &scene_;
    std::vector<Input> inputs_;
    EventLoop *loop_ = nullptr;
    std::optional<Timer> tick_;
};

} // namespace overlayd
