// SPDX-License-Identifier: Apache-2.0
// FolderWatch: a folder watched with inotify by its path, not by its inode. A folder that is removed, moved away or
// made again (systemd removes and re-creates a service's RuntimeDirectory= on every restart) is waited for on its
// nearest existing ancestor and watched again as soon as it is back.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"
#include "base/unique_fd.h"

namespace overlayd {

class FolderWatch
{
public:
    // At most this many looks up and down the path per re-arm: folders made or removed while we look (mkdir -p of a
    // deep path racing with us) cannot keep us looping.
    static constexpr int kMaxRearmSteps = 64;

    // Watches `folder` for `events` (IN_* of its files). The folder must exist now: a path that never existed is a
    // mistake to report, not to wait for.
    static Result<FolderWatch> open(const std::string &folder, uint32_t events);

    // Readable when something happened; consume() then says whether it concerned the file `name` in the folder.
    int fd() const { return fd_.get(); }
    // Reads every pending event. True when one was about `name`, or when the folder was watched again (or events
    // were lost): then anything in it may have changed.
    bool consume(std::string_view name);

    // Whether the folder itself is watched; otherwise problem() says why and which ancestor is watched for it.
    bool following() const { return folderWd_ >= 0; }
    const std::string &problem() const { return problem_; }
    const std::string &folder() const { return folder_; }

private:
    FolderWatch(UniqueFd fd, std::string folder, uint32_t events, int folderWd)
        : fd_(std::move(fd)), folder_(std::move(folder)), events_(events), folderWd_(folderWd)
    {}
    void rearm();
    // Watches the nearest existing ancestor for the folder's way back; false when a step of the way appeared
    // meanwhile (look again).
    bool waitInAncestor(int folderErrno);
    void drop(int &wd);

    UniqueFd fd_;
    std::string folder_;
    uint32_t events_;
    int folderWd_ = -1, ancestorWd_ = -1;
    std::string problem_;
};

} // namespace overlayd
