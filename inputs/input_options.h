// SPDX-License-Identifier: Apache-2.0
// What [[input.text]], [[input.path]] and [[input.can]] ask for: live data from outside the config file, into the
// running scene (text slots, world points, and the guide lines' steering angle).
// Compared whole (defaulted ==), so that a reload re-opens exactly the inputs that changed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "inputs/can_signal.h"
#include "inputs/can_socket.h"

namespace overlayd {

inline constexpr size_t kMaxTextInputs = 32;
inline constexpr size_t kMaxCanInputs = 16;
inline constexpr int kMaxCanTimeoutMs = 60000;
inline constexpr size_t kMaxInputTextBytes = 256; // a slot's limit (overlay/shapes/text_tokens.h kMaxSlotTextBytes)

// A text slot fed by a file another program writes: its first line, on the next frame after each change.
struct TextInputOptions {
    std::string slot; // a {slot:NAME} some text annotation shows
    std::string file; // absolute (resolved against the config's folder)
    size_t maxBytes = kMaxInputTextBytes;
    bool operator==(const TextInputOptions &) const = default;
};

inline constexpr size_t kMaxPathInputs = 16;

// The points of a polyline or markers annotation, from a file another program writes (point_list.h).
struct PathInputOptions {
    std::string annotation;
    std::string file; // absolute (resolved against the config's folder)
    bool operator==(const PathInputOptions &) const = default;
};

// What a CAN signal drives.
struct CanTarget {
    enum class Kind { Steering, Slot } kind = Kind::Steering;
    std::string name; // the guide-lines annotation, or the {slot:NAME}
    bool operator==(const CanTarget &) const = default;
};

// One signal on a SocketCAN interface. A value outside [min, max], or none for timeoutMs, is not shown as if it
// were true: the steering target hides its wheel tracks, a slot shows staleText.
struct CanInputOptions {
    std::string name;
    std::string interface;
    CanId id;
    CanSignalLayout layout;
    std::string unit;
    double min = -1e300, max = 1e300;
    int timeoutMs = 500;
    double step = 0.0; // a new value reaches the scene only when it differs from the shown one by at least this
    int decimals = 1;  // a slot's text: the value with this many decimals, then the unit
    std::string staleText = "--";
    CanTarget target;
    bool operator==(const CanInputOptions &) const = default;
};

struct InputOptions {
    std::vector<TextInputOptions> text;
    std::vector<PathInputOptions> paths;
    std::vector<CanInputOptions> can;
    bool empty() const { return text.empty() && paths.empty() && can.empty(); }
    bool operator==(const InputOptions &) const = default;
};

} // namespace overlayd
