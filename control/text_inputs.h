// SPDX-License-Identifier: Apache-2.0
// TextInputs: [[input.text]] at run time. Each file's folder is watched in the event loop; when the file changes,
// its first line goes into its text slot through SceneControl and shows from the next frame on.
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

class TextInputs final : public StatusReporter
{
public:
    TextInputs(Logger &logger, SceneControl &scene)
        : logger_(logger), scene_(scene), files_(logger, "text", [this](size_t input) { show(input); })
    {}

    // Watches every file (replacing the watches of the previous config) and shows what each holds now. A folder
    // that cannot be watched is an error, and the previous watches stay.
    Status configure(const std::vector<TextInputOptions> &options);
    // Puts every file's current line into its slot again (a new scene was loaded).
    void showAll();
    // Adds the watches' fds to the loop (null: removes them).
    void attachLoop(EventLoop *loop) { files_.attachLoop(loop); }

    struct Reading {
        std::string slot, file, text;
        std::string error; // why the file's last line was refused ("" when it is shown); the text shown stays
        std::chrono::steady_clock::time_point changed; // when the text last changed
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
