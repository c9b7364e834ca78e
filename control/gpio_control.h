// SPDX-License-Identifier: Apache-2.0
// GpioControl: the daemon's GPIO lines. Input edges are loop events (the line's fd in epoll) settled by a per-line
// debounce timerfd (libgpiod v1 has no debounce), and switch layers through SceneControl like any other change;
// outputs follow the daemon's state. A line that fails at run time is logged, released and requested again every
// few seconds: the stream never stops for GPIO.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/event_loop.h"
#include "base/logger.h"
#include "control/run_state.h"
#include "control/scene_control.h"
#include "control/status_reporter.h"
#include "gpio/line_provider.h"

namespace overlayd {

class GpioControl final : public StatusReporter
{
public:
    using State = RunState;
    static constexpr std::chrono::seconds kRetryPeriod{2};

    GpioControl(Logger &logger, SceneControl &scene) : logger_(logger), scene_(scene) {}
    ~GpioControl();

    // The provider the lines come from (libgpiod, or a fake in tests); set before the first configure().
    void setProvider(std::unique_ptr<LineProvider> provider) { provider_ = std::move(provider); }

    // Requests the lines of `options`, keeping those whose options did not change and releasing the rest. All or
    // nothing: on failure the previous lines are held again and the error names the line (and who holds it). Input
    // states are read, not assumed; call applyLayers() once the scene that names their layers is loaded.
    Status configure(const GpioOptions &options);
    // Every layer the inputs decide, set through SceneControl (all of them after configure, then only changes).
    void applyLayers();
    // Adds the input fds and timers to the loop (null: removes them).
    void attachLoop(EventLoop *loop);

    // Loop handlers, public so that tests drive them without a loop.
    void onEdge(size_t input);
    void onDebounced(size_t input);
    void onRetry();
    // The daemon's state after each loop turn, and each delivered frame (`sinkFailures`: the sinks' failed writes
    // so far, for `error` outputs).
    void onState(State state);
    void onFrameDelivered(uint64_t sinkFailures);
    bool wantsSinkFailures() const;
    // Clean stop: every output to its inactive level, every line released.
    void shutdown();

    // "reverse 1, status-led 0" (inputs settled, outputs as driven; "lost" while a line is being retried)
    std::string describe() const;
    // Its entries in /state and its samples in /metrics.
    void report(StatusReport &report) const override;
    bool empty() const { return inputs_.empty() && outputs_.empty(); }
    bool inputActive(size_t input) const { return inputs_.at(input).settled; }
    bool outputActive(size_t output) const { return outputs_.at(output).level; }

private:
    struct Input {
        GpioInputOptions options;
        std::unique_ptr<InputLine> line; // null while lost
        std::optional<Timer> debounce;
        bool settled = false;
    };
    struct Output {
        OutputOptions options;
        std::unique_ptr<OutputLine> line; // null while lost
        bool level = false;
    };

    Status requestInput(Input &input);
    Status requestOutput(Output &output);
    void lose(Input &input, const Error &error);
    void lose(Output &output, const Error &error);
    void drive(Output &output, bool level);
    bool wanted(const Output &output) const;
    void readInput(Input &input);
    void wire(bool add);
    void armRetry();

    Logger &logger_;
    SceneControl &scene_;
    std::unique_ptr<LineProvider> provider_;
    std::vector<Input> inputs_;
    std::vector<Output> outputs_;
    std::map<std::string, bool> applied_; // the layer visibility last set
    bool layersApplied_ = false;
    std::optional<Timer> retry_;
    EventLoop *loop_ = nullptr;
    State state_ = State::Idle;
    uint64_t sinkFailures_ = 0;
    bool failedLastFrame_ = false;
};

} // namespace overlayd
