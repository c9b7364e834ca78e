// SPDX-License-Identifier: Apache-2.0
#include "control/watched_files.h"

#include <algorithm>

#include "control/status_report.h"

namespace overlayd {

void WatchedFiles::replace(std::vector<TextFileWatch> watches, const std::vector<std::string> &names)
{
    std::vector<InputHealth> health;
    const auto now = InputHealth::Clock::now();
    for (size_t i = 0; i < watches.size(); ++i) {
        InputHealth next{kind_, names[i], watches[i].path(), InputHealth::State::Following, now};
        const auto before =
            std::find_if(health_.begin(), health_.end(), [&](const InputHealth &old) { return old.sameInput(next); });
        if (before != health_.end())
            next.keepHistory(*before);
        health.push_back(std::move(next));
    }
    wire(false);
    watches_ = std::move(watches);
    health_ = std::move(health);
    wire(true);
}

void WatchedFiles::attachLoop(EventLoop *loop)
{
    wire(false);
    loop_ = loop;
    wire(true);
}

void WatchedFiles::onEvent(size_t file)
{
    TextFileWatch &watch = watches_[file];
    const bool changed = watch.consume();
    InputHealth &health = health_[file];
    const std::string input = cat("input.", kind_, " '", health.name, "': ");
    if (health.enter(watch.following() ? InputHealth::State::Following : InputHealth::State::Waiting)) {
        if (watch.following()) {
            logger_.info(cat(input, "following ", watch.path(), " again"));
        } else {
            health.fail(watch.problem());
            logger_.warning(cat(input, watch.problem(), " (read as a missing file until it is back)"));
        }
    }
    if (changed)
        changed_(file);
}

void WatchedFiles::wire(bool add)
{
    if (!loop_)
        return;
    for (size_t i = 0; i < watches_.size(); ++i) {
        if (add)
            (void)loop_->add(watches_[i].fd(), [this, i] { onEvent(i); });
        else
            loop_->remove(watches_[i].fd());
    }
}

void WatchedFiles::report(StatusReport &report) const
{
    for (const InputHealth &input : health_)
        report.health(input);
}

} // namespace overlayd
