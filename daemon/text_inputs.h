// TextInputs: [[input.text]] at run time. Each file's folder is watched in the event loop; when the file changes,
// its first line goes into its text slot through SceneControl and shows from the next frame on.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "base/logger.h"
#include "daemon/event_loop.h"
#include "daemon/scene_control.h"
#include "inputs/input_options.h"
#include "inputs/text_file_watch.h"

namespace overlayd {

class TextInputs
{
public:
    TextInputs(Logger &logger, SceneControl &scene) : logger_(logger), scene_(scene) {}

    // Watches every file (replacing the watches of the previous config) and shows what each holds now. A folder
    // that cannot be watched is an error, and the previous watches stay.
    Status configure(const std::vector<inputs::TextInputOptions> &options);
    // Puts every file's current line into its slot again (a new scene was loaded).
    void showAll();
    // Adds the watches' fds to the loop (null: removes them).
    void attachLoop(EventLoop *loop);

    struct Reading {
        std::string slot, file, text;
        std::chrono::steady_clock::time_point changed; // when the text last changed
    };
    const std::vector<Reading> &readings() const { return readings_; }

private:
    void wire(bool add);
    void show(size_t input);

    Logger &logger_;
    SceneControl &scene_;
    std::vector<inputs::TextFileWatch> watches_;
    std::vector<Reading> readings_;
    EventLoop *loop_ = nullptr;
};

} // namespace overlayd
