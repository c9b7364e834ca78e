// SPDX-License-Identifier: Apache-2.0
// StatusReporter: a part of the running daemon (a sink, GPIO, each kind of input) that tells /state and /metrics
// about itself. The HTTP API asks every reporter the daemon lists and writes out what they add: a new kind of input
// or sink reports itself, and the API needs no edit.
#pragma once

namespace overlayd {

class StatusReport;

class StatusReporter
{
public:
    // Adds this part's /state entries and /metrics samples (control/status_report.h). Loop thread.
    virtual void report(StatusReport &report) const = 0;

protected:
    ~StatusReporter() = default;
};

} // namespace overlayd
