// SPDX-License-Identifier: Apache-2.0
// LineProvider: the few GPIO calls overlayd makes (request an input with edge events, request an output, list the
// chips), so that libgpiod's API (v1 in Debian 12, a different v2 in Debian 13) stays in one file behind it and the
// daemon's rules are tested with a fake.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/result.h"
#include "gpio/gpio_options.h"

namespace overlayd {

// A requested input with both edges as events. Values are logical: active-low is applied by the kernel.
class InputLine
{
public:
    virtual ~InputLine() = default;
    // Readable when an edge event is pending.
    virtual int fd() const = 0;
    // Reads the pending edge events (their number; what they say is read again with active()).
    virtual Result<unsigned> drainEvents() = 0;
    virtual Result<bool> active() = 0;
};

// A requested output; released (back to an input, the kernel's default) when destroyed.
class OutputLine
{
public:
    virtual ~OutputLine() = default;
    virtual Status setActive(bool active) = 0;
};

struct InputRequest {
    LineAddress line;
    bool activeLow = false;
    Bias bias = Bias::AsIs;
};

struct OutputRequest {
    LineAddress line;
    bool activeLow = false;
    bool active = false; // the level it starts at
};

struct LineInfo {
    unsigned offset = 0;
    std::string name;     // empty when the chip does not name it
    std::string consumer; // who holds it; empty when free
    bool output = false, activeLow = false;
};

struct ChipInfo {
    std::string name, label, path;
    std::vector<LineInfo> lines;
};

class LineProvider
{
public:
    virtual ~LineProvider() = default;
    // NotFound (chip or line; the message lists the chip's lines); Io (held by another consumer, named; or a failure).
    virtual Result<std::unique_ptr<InputLine>> requestInput(const InputRequest &request,
                                                            const std::string &consumer) = 0;
    virtual Result<std::unique_ptr<OutputLine>> requestOutput(const OutputRequest &request,
                                                              const std::string &consumer) = 0;
};

// libgpiod's provider, or (built without libgpiod) one that refuses every request saying so.
std::unique_ptr<LineProvider> makeLineProvider();
// Every GPIO chip and its lines; empty when there are none.
Result<std::vector<ChipInfo>> listChips();
// Whether this overlayd was built with libgpiod.
bool haveLibgpiod();

} // namespace overlayd
