// SPDX-License-Identifier: Apache-2.0
// What [[gpio.input]] and [[gpio.output]] ask for: lines by chip and name or offset, what an input switches and what
// an output shows. Compared whole (defaulted ==), so that a reload re-requests exactly the lines that changed.
#pragma once

#include <string>
#include <vector>

namespace overlayd {

// Limits: a board has a few dozen lines at most that mean anything to a camera.
inline constexpr size_t kMaxInputs = 32, kMaxOutputs = 32, kMaxLayersPerInput = 64;
inline constexpr unsigned kMaxDebounceMs = 10000;

enum class Bias { AsIs, Disable, PullUp, PullDown };

// A line: `chip` as libgpiod looks it up (name "gpiochip0", label, /dev path or number), then the line's name or,
// when `name` is empty, its offset.
struct LineAddress {
    std::string chip;
    std::string name;
    unsigned offset = 0;

    // "gpiochip0 line 17" or "gpiochip0 line 'REVERSE_IN'"
    std::string describe() const;
    // The same line however its chip is spelt as libgpiod looks it up: "gpiochip0", "/dev/gpiochip0" and "0" are
    // one chip (a label is known only on the machine, so it compares as written).
    bool sameLine(const LineAddress &other) const;
    bool operator==(const LineAddress &) const = default;
};

struct GpioInputOptions {
    std::string name;
    LineAddress line;
    bool activeLow = false;
    Bias bias = Bias::AsIs;
    unsigned debounceMs = 20;
    std::vector<std::string> showLayers; // visible only while the line is active
    std::vector<std::string> hideLayers; // hidden while it is active
    bool operator==(const GpioInputOptions &) const = default;
};

// What an output line shows: frames flowing (the watchdog's rule), the NO SIGNAL state, sink write failures, or a
// level that flips with every frame delivered.
enum class OutputSignal { Streaming, NoSignal, Error, FrameToggle };

struct OutputOptions {
    std::string name;
    LineAddress line;
    OutputSignal signal = OutputSignal::Streaming;
    bool activeLow = false;
    bool operator==(const OutputOptions &) const = default;
};

struct GpioOptions {
    std::vector<GpioInputOptions> inputs;
    std::vector<OutputOptions> outputs;
    bool empty() const { return inputs.empty() && outputs.empty(); }
    bool operator==(const GpioOptions &) const = default;
};

} // namespace overlayd
