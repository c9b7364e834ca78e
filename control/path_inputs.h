// SPDX-License-Identifier: Apache-2.0
// PathInputs: [[input.path]] at run time. Each file's folder is watched in the event loop (inotify); when the file
// changes, its points replace its annotation's through SceneControl from the next frame on. A file that does not
// parse is logged (file:line) and the points shown stay: bad input loses nothing.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "base/event_loop.h"
#include "base/logger.h"
#include "control/scene_control.h"
#include "control/status_reporter.h"
#include "control/watched_files.h"
#include "inputs/input_options.h"

namespace overlayd {

class PathInputs final : public StatusReporter
{
public:
    PathInputs(Logger &logger, SceneControl &scene)
        : logger_(logger), scene_(scene), files_(logger, "path", [this](size_t input) { show(input); })
    {}

    // Watches every file (replacing the previous watches); showAll() then shows what each holds (after a reload's
    // new scene is in place, which may be the first to have the annotations). A folder that cannot be watched is an
    // error, and the previous watches stay.
    Status configure(const std::vector<PathInputOptions> &options);
    // Shows every file's points again (a new scene was loaded).
    void showAll();
    void attachLoop(EventLoop *loop) { files_.attachLoop(loop); }

    struct Reading {
        std::string annotation, file;
        size_t points = 0;
        std::string error;                             // why the file's last version was refused ("" when it was shown)
        std::chrono::steady_clock::time_point changed; // when the points shown last changed
    };
    const std::vector<Reading> &readings() const { return readings_; }
    // Each input's health: following its file or waiting for its folder, and its last error.
    const std::vector<InputHealth> &health() const { return files_.health(); }
    // Its entries in /state and its samples in /metrics.
    void report(StatusReport &report) const override;

private:
    void show(size_t input);

    Logger &logger_;
    SceneControl &scene_;
    WatchedFiles files_;
    std::vector<Reading> readings_;
};

} // namespace overlayd
