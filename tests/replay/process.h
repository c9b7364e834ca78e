// SPDX-License-Identifier: Apache-2.0
// A long-running `overlayd run` for the replay tests: started in a scratch folder with its stderr in a file, and
// polled (not timed) until what it writes shows a condition.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include <sys/types.h>

namespace overlayd::test {

// `overlayd run --config CONFIG` in `dir`, stderr to dir/overlayd.stderr, with JOURNAL_STREAM set (so log lines carry
// syslog priority prefixes). Returns once the child has exec'd the binary, so that a signal sent from then on is
// sent to overlayd, not to the harness's fork. blockStopSignals: SIGTERM and SIGINT are blocked across the exec,
// as a supervisor can start it (they stay pending until overlayd reads them). The caller signals and reaps it.
pid_t startDaemon(const std::string &dir, const std::string &config, bool blockStopSignals = false);

// How a process ended: its exit status, or the signal that killed it; nothing when it is still running at the limit
// (it is then killed, so that a test never leaves one behind).
struct Ending {
    int exitStatus = -1; // -1: killed by a signal
    int signal = 0;
    bool coreDumped = false;
};
std::optional<Ending> waitForExit(pid_t pid, std::chrono::milliseconds limit);

// Polls until the condition holds (not a timed assertion: the limit only keeps a broken daemon from hanging CI).
bool waitFor(const std::function<bool()> &condition, std::chrono::seconds limit = std::chrono::seconds(20));

// A whole file as text; empty when it cannot be read.
std::string fileText(const std::string &path);

} // namespace overlayd::test
