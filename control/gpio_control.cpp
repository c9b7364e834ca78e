// SPDX-License-Identifier: Apache-2.0
// GpioControl: requesting and re-requesting lines, debounced input edges into layer changes, outputs that follow
// the daemon's state.
#include "control/gpio_control.h"

#include "control/status_report.h"
#include "gpio/layer_rules.h"

namespace overlayd {

namespace {

constexpr const char *kConsumer = "overlayd"; // what gpioinfo shows as the lines' holder

// The entries of `next` take the held lines of `old` whose options are unchanged; the others are requested. All or
// nothing: on failure every reused line goes back to `old`, whose released lines are requested again (what fails
// then stays lost and is retried). `bestEffort`: a line that cannot be requested stays lost instead.
template<typename Entry, typename Options, typename Request>
Status reconfigure(std::vector<Entry> &old, const std::vector<Options> &options, std::vector<Entry> &next,
                   Request request, bool bestEffort = false)
{
    std::vector<Options> previous;
    for (const Entry &entry : old)
        previous.push_back(entry.options);
    std::vector<int> from(options.size(), -1);
    std::vector<bool> taken(old.size(), false);
    next.clear();
    for (size_t i = 0; i < options.size(); ++i) {
        Entry &entry = next.emplace_back();
        entry.options = options[i];
        for (size_t j = 0; j < old.size(); ++j)
            if (!taken[j] && old[j].line && previous[j] == options[i]) {
                taken[j] = true;
                from[i] = int(j);
                entry = std::move(old[j]);
                break;
            }
    }
    for (size_t j = 0; j < old.size(); ++j)
        if (!taken[j])
            old[j].line.reset(); // released first: a changed line may be the same physical line
    for (size_t i = 0; i < next.size(); ++i) {
        if (from[i] >= 0)
            continue;
        Status requested = request(next[i]);
        if (requested)
            continue;
        next[i].line.reset();
        if (bestEffort)
            continue;
        for (size_t k = 0; k < next.size(); ++k)
            if (from[k] >= 0)
                old[size_t(from[k])] = std::move(next[k]);
        next.clear();
        for (size_t j = 0; j < old.size(); ++j) {
            old[j].options = previous[j];
            if (!taken[j] && !request(old[j]))
                old[j].line.reset();
        }
        return requested;
    }
    return Ok{};
}

} // namespace

GpioControl::~GpioControl()
{
    wire(false);
}

Status GpioControl::requestInput(Input &input)
{
    const GpioInputOptions &o = input.options;
    auto line = provider_->requestInput({o.line, o.activeLow, o.bias}, kConsumer);
    if (!line)
        return makeError(line.error().code, "gpio input '" + o.name + "': " + line.error().message);
    input.line = std::move(*line);
    if (o.debounceMs > 0 && !input.debounce) {
        auto timer = Timer::create();
        if (!timer)
            return timer.error();
        input.debounce.emplace(std::move(*timer));
    }
    if (auto active = input.line->active())
        input.settled = *active;
    else
        return makeError(active.error().code, "gpio input '" + o.name + "': " + active.error().message);
    return Ok{};
}

Status GpioControl::requestOutput(Output &output)
{
    const OutputOptions &o = output.options;
    output.level = wanted(output);
    auto line = provider_->requestOutput({o.line, o.activeLow, output.level}, kConsumer);
    if (!line)
        return makeError(line.error().code, "gpio output '" + o.name + "': " + line.error().message);
    output.line = std::move(*line);
    return Ok{};
}

Status GpioControl::configure(const GpioOptions &options)
{
    if (!provider_)
        return makeError(ErrorCode::InvalidArgument, "gpio: no line provider");
    if (!retry_) {
        auto timer = Timer::create();
        if (!timer)
            return timer.error();
        retry_.emplace(std::move(*timer));
    }
    wire(false);
    std::vector<GpioInputOptions> previousInputs;
    for (const Input &input : inputs_)
        previousInputs.push_back(input.options);
    std::vector<Input> inputs;
    std::vector<Output> outputs;
    const auto requestIn = [this](Input &in) {
        return requestInput(in);
    };
    Status result = reconfigure(inputs_, options.inputs, inputs, requestIn);
    if (result) {
        result = reconfigure(outputs_, options.outputs, outputs, [this](Output &out) { return requestOutput(out); });
        if (result) {
            inputs_ = std::move(inputs);
            outputs_ = std::move(outputs);
            layersApplied_ = false;
        } else { // the inputs go back too: all or nothing
            std::vector<Input> restored;
            (void)reconfigure(inputs, previousInputs, restored, requestIn, true);
            inputs_ = std::move(restored);
        }
    }
    for (const Input &input : inputs_)
        if (!input.line)
            armRetry();
    for (const Output &output : outputs_)
        if (!output.line)
            armRetry();
    wire(true);
    return result;
}

void GpioControl::applyLayers()
{
    std::vector<GpioInputOptions> options;
    std::vector<bool> active;
    for (const Input &input : inputs_) {
        options.push_back(input.options);
        active.push_back(input.settled);
    }
    for (const auto &[layer, visible] : layerVisibility(options, active)) {
        const auto last = applied_.find(layer);
        if (layersApplied_ && last != applied_.end() && last->second == visible)
            continue;
        if (Status applied = scene_.apply(LayerChange{layer, visible}); !applied)
            logger_.error("gpio: layer '" + layer + "': " + applied.error().message);
        applied_[layer] = visible;
    }
    layersApplied_ = true;
}

void GpioControl::readInput(Input &input)
{
    auto active = input.line->active();
    if (!active) {
        lose(input, active.error());
        return;
    }
    if (*active == input.settled)
        return;
    input.settled = *active;
    logger_.info("gpio: input '" + input.options.name + "' " + (*active ? "active" : "inactive"));
    applyLayers();
}

void GpioControl::onEdge(size_t index)
{
    Input &input = inputs_.at(index);
    if (!input.line)
        return;
    if (auto drained = input.line->drainEvents(); !drained) {
        lose(input, drained.error());
        return;
    }
    // Every edge restarts the debounce: the level is read once the line has been quiet that long.
    if (input.debounce)
        (void)input.debounce->arm(std::chrono::milliseconds(input.options.debounceMs));
    else
        readInput(input);
}

void GpioControl::onDebounced(size_t index)
{
    Input &input = inputs_.at(index);
    if (input.debounce)
        input.debounce->consume();
    if (input.line)
        readInput(input);
}

void GpioControl::lose(Input &input, const Error &error)
{
    logger_.error("gpio input '" + input.options.name + "': " + error.message + "; requesting it again every " +
                  std::to_string(kRetryPeriod.count()) + " s");
    if (loop_ && input.line)
        loop_->remove(input.line->fd());
    input.line.reset();
    armRetry();
}

void GpioControl::lose(Output &output, const Error &error)
{
    logger_.error("gpio output '" + output.options.name + "': " + error.message + "; requesting it again every " +
                  std::to_string(kRetryPeriod.count()) + " s");
    output.line.reset();
    armRetry();
}

void GpioControl::armRetry()
{
    if (retry_)
        (void)retry_->arm(kRetryPeriod, kRetryPeriod);
}

void GpioControl::onRetry()
{
    if (retry_)
        retry_->consume();
    bool missing = false;
    for (size_t i = 0; i < inputs_.size(); ++i) {
        Input &input = inputs_[i];
        if (input.line)
            continue;
        if (Status requested = requestInput(input); !requested) {
            input.line.reset();
            missing = true;
            continue;
        }
        logger_.notice("gpio input '" + input.options.name + "' is back");
        if (loop_)
            (void)loop_->add(input.line->fd(), [this, i] { onEdge(i); });
        applyLayers();
    }
    for (Output &output : outputs_) {
        if (output.line)
            continue;
        if (Status requested = requestOutput(output); !requested) {
            missing = true;
            continue;
        }
        logger_.notice("gpio output '" + output.options.name + "' is back");
    }
    if (!missing && retry_)
        retry_->disarm();
}

bool GpioControl::wanted(const Output &output) const
{
    switch (output.options.signal) {
    case OutputSignal::Streaming:
        return state_ == State::Streaming;
    case OutputSignal::NoSignal:
        return state_ == State::Waiting;
    case OutputSignal::Error:
        return failedLastFrame_;
    case OutputSignal::FrameToggle:
        return output.level;
    }
    return false;
}

void GpioControl::drive(Output &output, bool level)
{
    if (output.level == level)
        return;
    output.level = level;
    if (output.line)
        if (Status set = output.line->setActive(level); !set)
            lose(output, set.error());
}

void GpioControl::onState(State state)
{
    if (state == state_)
        return;
    state_ = state;
    if (state != State::Streaming)
        failedLastFrame_ = false;
    for (Output &output : outputs_)
        drive(output, wanted(output));
}

bool GpioControl::wantsSinkFailures() const
{
    for (const Output &output : outputs_)
        if (output.options.signal == OutputSignal::Error)
            return true;
    return false;
}

void GpioControl::onFrameDelivered(uint64_t sinkFailures)
{
    failedLastFrame_ = sinkFailures > sinkFailures_;
    sinkFailures_ = sinkFailures;
    state_ = State::Streaming;
    for (Output &output : outputs_)
        drive(output, output.options.signal == OutputSignal::FrameToggle ? !output.level : wanted(output));
}

void GpioControl::shutdown()
{
    wire(false);
    for (Output &output : outputs_)
        drive(output, false);
    outputs_.clear();
    inputs_.clear();
}

void GpioControl::attachLoop(EventLoop *loop)
{
    wire(false);
    loop_ = loop;
    wire(true);
}

void GpioControl::wire(bool add)
{
    if (!loop_)
        return;
    for (size_t i = 0; i < inputs_.size(); ++i) {
        Input &input = inputs_[i];
        if (input.debounce) {
            if (add)
                (void)loop_->add(input.debounce->fd(), [this, i] { onDebounced(i); });
            else
                loop_->remove(input.debounce->fd());
        }
        if (!input.line)
            continue;
        if (add)
            (void)loop_->add(input.line->fd(), [this, i] { onEdge(i); });
        else
            loop_->remove(input.line->fd());
    }
    if (retry_) {
        if (add)
            (void)loop_->add(retry_->fd(), [this] { onRetry(); });
        else
            loop_->remove(retry_->fd());
    }
}

std::string GpioControl::describe() const
{
    std::string text;
    const auto add = [&text](const std::string &name, bool held, bool level) {
        text += (text.empty() ? "" : ", ") + name + (held ? (level ? " 1" : " 0") : " lost");
    };
    for (const Input &input : inputs_)
        add(input.options.name, input.line != nullptr, input.settled);
    for (const Output &output : outputs_)
        add(output.options.name, output.line != nullptr, output.level);
    return text;
}

void GpioControl::report(StatusReport &report) const
{
    if (!empty())
        report.set("gpio", describe());
}

} // namespace overlayd
