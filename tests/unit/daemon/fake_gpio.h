// SPDX-License-Identifier: Apache-2.0
// FakeGpio: a LineProvider over simulated lines, as gpio-sim is in the VM tier: the test sets a line's physical
// level (an edge event fires on its eventfd), reads what outputs drive, makes a line busy or lost.
#pragma once

#include <sys/eventfd.h>
#include <unistd.h>

#include <map>
#include <memory>
#include <string>

#include "base/unique_fd.h"
#include "gpio/line_provider.h"

namespace overlayd::test {

class FakeGpio
{
public:
    struct Line {
        bool physical = false;  // the level on the wire
        std::string consumer;   // who holds it; empty: free
        bool lost = false;      // the chip went away: every call fails
        bool activeLow = false; // as requested
        Bias bias = Bias::AsIs;
        UniqueFd events{::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)};
        unsigned requests = 0;
    };

    // The line for a chip and name (created on first use: every line exists unless `missing` says otherwise).
    Line &line(const std::string &chip, const std::string &name) { return lines_[chip + "/" + name]; }
    // A physical level change, with its edge event.
    void set(const std::string &chip, const std::string &name, bool physical)
    {
        Line &l = line(chip, name);
        l.physical = physical;
        const uint64_t one = 1;
        (void)!::write(l.events.get(), &one, sizeof(one));
    }
    // What an output drives now (logical, active-low applied back), or an input reads.
    bool logical(const std::string &chip, const std::string &name)
    {
        Line &l = line(chip, name);
        return l.physical != l.activeLow;
    }
    std::string missingChip; // requests on this chip fail as NotFound

    std::unique_ptr<LineProvider> provider();

private:
    std::map<std::string, Line> lines_;
};

} // namespace overlayd::test
