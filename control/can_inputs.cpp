// SPDX-License-Identifier: Apache-2.0
#include "control/can_inputs.h"

#include <algorithm>
#include <cmath>

#include "control/status_report.h"
#include "inputs/can_signal.h"

namespace overlayd {

const char *CanInputs::stateName(State state)
{
    switch (state) {
    case State::NoData:
        return "no-data";
    case State::Ok:
        return "ok";
    case State::Stale:
        return "stale";
    case State::OutOfRange:
        return "out-of-range";
    }
    return "?";
}

void CanInputs::configure(const std::vector<CanInputOptions> &options)
{
    EventLoop *loop = loop_;
    attachLoop(nullptr);
    std::vector<Input> next;
    for (const CanInputOptions &option : options) {
        auto same = std::find_if(inputs_.begin(), inputs_.end(), [&](const Input &input) {
            return input.options == option && !input.options.name.empty();
        });
        if (same != inputs_.end()) {
            next.push_back(std::move(*same));
            same->options.name.clear(); // taken
        } else {
            InputHealth health("can", option.name, option.interface, InputHealth::State::Waiting, Clock::now());
            next.push_back(Input{option, std::nullopt, {}, {}, std::nullopt, false, std::move(health)});
        }
    }
    inputs_ = std::move(next);
    const Clock::time_point now = Clock::now();
    for (size_t i = 0; i < inputs_.size(); ++i)
        if (!inputs_[i].socket)
            open(i, now);
    attachLoop(loop);
    showAll();
}

void CanInputs::showAll()
{
    for (size_t i = 0; i < inputs_.size(); ++i)
        show(i, true);
}

void CanInputs::attachLoop(EventLoop *loop)
{
    if (loop_) {
        for (size_t i = 0; i < inputs_.size(); ++i)
            wire(i, false);
        if (tick_)
            loop_->remove(tick_->fd());
    }
    loop_ = loop;
    if (!loop_ || inputs_.empty())
        return;
    if (!tick_) {
        auto timer = Timer::create();
        if (!timer) {
            logger_.error("input.can: no tick timer: " + timer.error().message);
            return;
        }
        tick_ = std::move(*timer);
        (void)tick_->arm(kTick, kTick);
    }
    (void)loop_->add(tick_->fd(), [this] {
        if (tick_->consume())
            tick(Clock::now());
    });
    for (size_t i = 0; i < inputs_.size(); ++i)
        wire(i, true);
}

void CanInputs::wire(size_t input, bool add)
{
    if (!loop_ || !inputs_[input].socket)
        return;
    const int fd = inputs_[input].socket->fd();
    if (add)
        (void)loop_->add(fd, [this, input] { readAll(input); });
    else
        loop_->remove(fd);
}

void CanInputs::open(size_t input, Clock::time_point now)
{
    Input &in = inputs_[input];
    in.nextOpen = now + kRetry;
    auto socket = CanSocket::open(in.options.interface, in.options.id);
    if (!socket) {
        if (socket.error().message != in.reading.error) { // once per new reason, not every second
            logger_.warning(cat("input.can '", in.options.name, "': ", socket.error().message, " (retrying)"));
            in.health.fail(socket.error().message);
        }
        in.reading.error = socket.error().message;
        return;
    }
    in.socket = std::move(*socket);
    in.reading.connected = true;
    in.reading.error.clear();
    in.health.enter(InputHealth::State::Following, now);
    logger_.info(cat("input.can '", in.options.name, "': reading ", in.options.interface));
    wire(input, true);
}

void CanInputs::close(size_t input, const std::string &why, Clock::time_point now)
{
    Input &in = inputs_[input];
    wire(input, false);
    in.socket.reset();
    in.reading.connected = false;
    in.reading.error = why;
    in.health.enter(InputHealth::State::Waiting, now);
    in.health.fail(why);
    in.nextOpen = now + kRetry;
    logger_.warning(cat("input.can '", in.options.name, "': ", why, " (retrying)"));
}

void CanInputs::readAll(size_t input)
{
    CanFrame frame;
    for (int n = 0; n < kMaxFramesPerWake && inputs_[input].socket; ++n) {
        auto got = inputs_[input].socket->read(frame);
        if (!got) {
            close(input, got.error().message, Clock::now());
            return;
        }
        if (!*got)
            return;
        onFrame(input, frame, Clock::now());
    }
}

void CanInputs::onFrame(size_t input, const CanFrame &frame, Clock::time_point now)
{
    Input &in = inputs_[input];
    Reading &r = in.reading;
    ++r.frames;
    const std::optional<double> value = canDecode(in.options.layout, frame.bytes());
    if (!value) { // too few data bytes for the signal (a wrong DLC)
        ++r.malformed;
        return;
    }
    r.value = *value;
    r.received = now;
    if (!(*value >= in.options.min && *value <= in.options.max)) {
        ++r.outOfRange;
        r.state = State::OutOfRange;
    } else {
        r.state = State::Ok;
        r.updated = now;
    }
    show(input, false);
}

void CanInputs::tick(Clock::time_point now)
{
    for (size_t i = 0; i < inputs_.size(); ++i) {
        Input &in = inputs_[i];
        if (!in.socket && now >= in.nextOpen)
            open(i, now);
        if (in.reading.state == State::Ok &&
            now - in.reading.updated > std::chrono::milliseconds(in.options.timeoutMs)) {
            in.reading.state = State::Stale;
            show(i, false);
        }
    }
}

void CanInputs::show(size_t input, bool force)
{
    Input &in = inputs_[input];
    const std::optional<double> value =
        in.reading.state == State::Ok ? std::optional<double>(in.reading.value) : std::nullopt;
    if (!force && in.everShown && value.has_value() == in.shown.has_value() &&
        (!value || *value == *in.shown || std::abs(*value - *in.shown) < in.options.step))
        return; // nothing the target shows would change (a steady wheel costs nothing)
    const CanTarget &target = in.options.target;
    Status applied = Ok{};
    if (target.kind == CanTarget::Kind::Steering)
        applied = scene_.apply(SteeringChange{target.name, value});
    else
        applied = scene_.apply(TextChange{
            target.name, value ? canReadingText(*value, in.options.decimals, in.options.unit) : in.options.staleText});
    if (!applied) {
        logger_.warning(cat("input.can '", in.options.name, "': ", applied.error().message));
        return;
    }
    if (in.everShown && value.has_value() != in.shown.has_value())
        logger_.info(cat("input.can '", in.options.name, "': ", stateName(in.reading.state)));
    in.shown = value;
    in.everShown = true;
}

std::vector<InputHealth> CanInputs::health() const
{
    std::vector<InputHealth> out;
    for (const Input &in : inputs_)
        out.push_back(in.health);
    return out;
}

std::string CanInputs::describe(Clock::time_point now) const
{
    std::string out;
    for (const Input &in : inputs_) {
        const Reading &r = in.reading;
        out += out.empty() ? "" : ", ";
        out += cat(in.options.name, "=");
        out +=
            r.state == State::NoData ? std::string("-") : canReadingText(r.value, in.options.decimals, in.options.unit);
        out += cat(" ", stateName(r.state));
        if (r.state != State::NoData)
            out += cat(" age ", std::chrono::duration_cast<std::chrono::milliseconds>(now - r.received).count(), " ms");
        if (r.malformed)
            out += cat(" malformed ", r.malformed);
        if (!r.connected)
            out += " (" + r.error + ")";
    }
    return out;
}

void CanInputs::report(StatusReport &report) const
{
    using nlohmann::json;
    for (const Input &in : inputs_) {
        const CanInputOptions &options = in.options;
        const Reading &reading = in.reading;
        const bool any = reading.state != State::NoData;
        json entry = {{"kind", "can"},
                      {"name", options.name},
                      {"interface", options.interface},
                      {"id", options.id.id},
                      {"target", options.target.kind == CanTarget::Kind::Slot ? "slot:" + options.target.name
                                                                              : options.target.name + ".steering"},
                      {"value", any ? json(reading.value) : json(nullptr)},
                      {"unit", options.unit},
                      {"state", stateName(reading.state)},
                      {"age_s", any ? json(std::chrono::duration<double>(report.now() - reading.received).count())
                                    : json(nullptr)},
                      {"frames", reading.frames},
                      {"malformed", reading.malformed},
                      {"out_of_range", reading.outOfRange},
                      {"connected", reading.connected}};
        if (!reading.connected)
            entry["error"] = reading.error; // also "" before the first attempt to open
        report.add("inputs", std::move(entry));
        const std::string label = StatusReport::label("input", options.name);
        report.metric("overlayd_can_frames_total", "counter", "CAN frames an input received.", double(reading.frames),
                      label);
        report.metric("overlayd_can_malformed_total", "counter", "CAN frames too short for the signal (ignored).",
                      double(reading.malformed), label);
        report.metric("overlayd_can_value_valid", "gauge", "1 while the signal's value is fresh and in range.",
                      reading.state == State::Ok ? 1.0 : 0.0, label);
    }
    for (const Input &in : inputs_)
        report.health(in.health);
}

} // namespace overlayd
