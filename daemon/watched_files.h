// WatchedFiles: the inotify watches of the file inputs ([[input.text]], [[input.path]]) and their place in the event
// loop; tells its owner which file changed.
#pragma once

#include <functional>
#include <vector>

#include "base/event_loop.h"
#include "inputs/text_file_watch.h"

namespace overlayd {

class WatchedFiles
{
public:
    using Changed = std::function<void(size_t file)>;
    explicit WatchedFiles(Changed changed) : changed_(std::move(changed)) {}

    // Swaps in new watches (the caller opened every one, so that one that fails leaves the old ones in place).
    void replace(std::vector<inputs::TextFileWatch> watches);
    // Adds the watches' fds to the loop (null: removes them).
    void attachLoop(EventLoop *loop);

    size_t size() const { return watches_.size(); }
    const inputs::TextFileWatch &operator[](size_t file) const { return watches_[file]; }

private:
    void wire(bool add);

    Changed changed_;
    std::vector<inputs::TextFileWatch> watches_;
    EventLoop *loop_ = nullptr;
};

} // namespace overlayd
