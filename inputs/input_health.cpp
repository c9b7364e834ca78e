// SPDX-License-Identifier: Apache-2.0
#include "inputs/input_health.h"

#include <utility>

namespace overlayd {

bool InputHealth::enter(State next, Clock::time_point now)
{
    if (state == next)
        return false;
    state = next;
    since = now;
    return true;
}

void InputHealth::fail(std::string message, WallClock::time_point at)
{
    ++errors;
    lastError = std::move(message);
    lastErrorAt = at;
}

void InputHealth::keepHistory(const InputHealth &before)
{
    errors = before.errors;
    lastError = before.lastError;
    lastErrorAt = before.lastErrorAt;
}

const char *inputStateName(InputHealth::State state)
{
    switch (state) {
    case InputHealth::State::Following:
        return "following";
    case InputHealth::State::Waiting:
        return "waiting";
    }
    return "?";
}

} // namespace overlayd
