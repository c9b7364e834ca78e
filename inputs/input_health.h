// SPDX-License-Identifier: Apache-2.0
// InputHealth: how one live input is doing, told the same way for every kind of input (a watched file, a CAN
// interface), so that what reports it (/state, /metrics, the log) needs no change when a kind is added. Each input
// collection keeps one per input and hands them out as a list.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

namespace overlayd {

struct InputHealth {
    using Clock = std::chrono::steady_clock;
    using WallClock = std::chrono::system_clock;
    // Following: the input reads its source (the file's folder is watched, the interface is open). Waiting: the
    // source is gone (a removed folder, an interface that is down or missing) and is waited for.
    enum class State { Following, Waiting };

    InputHealth(std::string ofKind, std::string named, std::string follows, State initial, Clock::time_point at)
        : kind(std::move(ofKind)), name(std::move(named)), source(std::move(follows)), state(initial), since(at)
    {}

    std::string kind;   // the [[input.KIND]] table: "text", "path", "can"
    std::string name;   // what the input's table names it by: the slot, the annotation, the CAN input's name
    std::string source; // what it follows: a file, an interface
    State state = State::Following;
    Clock::time_point since; // when it entered `state`
    uint64_t errors = 0;     // errors met, kept over a reload that keeps the input
    std::string lastError;   // the latest error ("" before the first), and when it happened
    WallClock::time_point lastErrorAt;

    // Enters `next` (since: now) unless it is in it already; true when it changed.
    bool enter(State next, Clock::time_point now = Clock::now());
    // Counts an error and keeps it as the latest.
    void fail(std::string message, WallClock::time_point at = WallClock::now());
    // Keeps the error count and the latest error of `before`, this input's health before a reload.
    void keepHistory(const InputHealth &before);
    bool sameInput(const InputHealth &other) const
    {
        return kind == other.kind && name == other.name && source == other.source;
    }
};

// "following", "waiting".
const char *inputStateName(InputHealth::State state);

} // namespace overlayd
