// A long-running `overlayd run` for the replay tests: started in a scratch folder with its stderr in a file, and
// polled (not timed) until what it writes shows a condition.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include <sys/types.h>

namespace overlayd::replay {

// `overlayd run --config CONFIG` in `dir`, stderr to dir/overlayd.stderr, with JOURNAL_STREAM set (so log lines carry
// syslog priority prefixes). The caller signals and reaps it.
pid_t startDaemon(const std::string &dir, const std::string &config);

// Polls until the condition holds (not a timed assertion: the limit only keeps a broken daemon from hanging CI).
bool waitFor(const std::function<bool()> &condition, std::chrono::seconds limit = std::chrono::seconds(20));

// A whole file as text; empty when it cannot be read.
std::string fileText(const std::string &path);

} // namespace overlayd::replay
