#include "daemon/watched_files.h"

namespace overlayd {

void WatchedFiles::replace(std::vector<inputs::TextFileWatch> watches)
{
    wire(false);
    watches_ = std::move(watches);
    wire(true);
}

void WatchedFiles::attachLoop(EventLoop *loop)
{
    wire(false);
    loop_ = loop;
    wire(true);
}

void WatchedFiles::wire(bool add)
{
    if (!loop_)
        return;
    for (size_t i = 0; i < watches_.size(); ++i) {
        if (!add) {
            loop_->remove(watches_[i].fd());
            continue;
        }
        (void)loop_->add(watches_[i].fd(), [this, i] {
            if (watches_[i].consume())
                changed_(i);
        });
    }
}

} // namespace overlayd
