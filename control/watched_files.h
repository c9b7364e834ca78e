// SPDX-License-Identifier: Apache-2.0
// WatchedFiles: the inotify watches of the file inputs ([[input.text]], [[input.path]]) and their place in the event
// loop; tells its owner which file changed, and keeps each input's health: following its file, or waiting for its
// folder to come back, and the last error.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "base/event_loop.h"
#include "base/logger.h"
#include "control/status_reporter.h"
#include "inputs/input_health.h"
#include "inputs/text_file_watch.h"

namespace overlayd {

class WatchedFiles
{
public:
    using Changed = std::function<void(size_t file)>;
    // kind: the [[input.KIND]] the files feed ("text", "path"), for the log and the health.
    WatchedFiles(Logger &logger, std::string kind, Changed changed)
        : logger_(logger), kind_(std::move(kind)), changed_(std::move(changed))
    {}

    // Swaps in new watches, one per input, named as its table names it (the caller opened every one, so that one
    // that fails leaves the old ones in place). An input watched before keeps its error count and last error.
    void replace(std::vector<TextFileWatch> watches, const std::vector<std::string> &names);
    // Adds the watches' fds to the loop (null: removes them).
    void attachLoop(EventLoop *loop);
    // What the loop runs when a watch's fd is readable; public for tests.
    void onEvent(size_t file);
    // Counts an error of the file's content (a version that was refused) in its health.
    void fail(size_t file, const std::string &message) { health_[file].fail(message); }

    size_t size() const { return watches_.size(); }
    const TextFileWatch &operator[](size_t file) const { return watches_[file]; }
    const std::vector<InputHealth> &health() const { return health_; }
    // Each file's health in /state and /metrics.
    void report(StatusReport &report) const;

private:
    void wire(bool add);

    Logger &logger_;
    std::string kind_;
    Changed changed_;
    std::vector<TextFileWatch> watches_;
    std::vector<InputHealth> health_;
    EventLoop *loop_ = nullptr;
};

} // namespace overlayd
