// SPDX-License-Identifier: Apache-2.0
#include "inputs/folder_watch.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sys/inotify.h>
#include <unistd.h>

namespace overlayd {

namespace {

// The folder itself went: removed (IN_DELETE_SELF, then IN_IGNORED), moved away, or its file system unmounted.
// IN_IGNORED and IN_UNMOUNT come without being asked for.
constexpr uint32_t kSelf = IN_DELETE_SELF | IN_MOVE_SELF;
constexpr uint32_t kGone = kSelf | IN_IGNORED | IN_UNMOUNT;
// What brings a missing folder, or a step of the way to it, back into an ancestor.
constexpr uint32_t kAppears = IN_CREATE | IN_MOVED_TO;

bool isFolder(const std::filesystem::path &path)
{
    std::error_code error;
    return std::filesystem::is_directory(path, error);
}

} // namespace

Result<FolderWatch> FolderWatch::open(const std::string &folder, uint32_t events)
{
    UniqueFd fd(::inotify_init1(IN_NONBLOCK | IN_CLOEXEC));
    if (fd.get() < 0)
        return makeError(ErrorCode::Io, std::string("inotify: ") + std::strerror(errno));
    const int wd = ::inotify_add_watch(fd.get(), folder.c_str(), events | kSelf | IN_ONLYDIR);
    if (wd < 0)
        return makeError(errno == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                         "cannot watch the folder " + folder + ": " + std::strerror(errno));
    return FolderWatch(std::move(fd), folder, events, wd);
}

bool FolderWatch::consume(std::string_view name)
{
    alignas(inotify_event) char buffer[4096];
    bool ours = false, look = false;
    for (;;) {
        const ssize_t got = ::read(fd_.get(), buffer, sizeof(buffer));
        if (got <= 0)
            break;
        for (ssize_t at = 0; at < got;) {
            const auto *event = reinterpret_cast<const inotify_event *>(buffer + at);
            at += ssize_t(sizeof(inotify_event) + event->len);
            if (event->mask & IN_Q_OVERFLOW)
                look = true; // events were lost, the folder's among them maybe
            else if (folderWd_ >= 0 && event->wd == folderWd_) {
                look = look || (event->mask & kGone) != 0;
                ours = ours || (event->len && name == event->name);
            } else if (ancestorWd_ >= 0 && event->wd == ancestorWd_)
                look = true; // a step of the way appeared, or the ancestor itself went
            // Any other wd is a watch already dropped (its IN_IGNORED).
        }
    }
    if (!look)
        return ours;
    const bool wasFollowing = following();
    rearm();
    // Lost, or found again: the file may be another one now. Still waiting: there is no file to read.
    return ours || wasFollowing || following();
}

void FolderWatch::rearm()
{
    drop(folderWd_);
    for (int step = 0; step < kMaxRearmSteps; ++step) {
        drop(ancestorWd_);
        folderWd_ = ::inotify_add_watch(fd_.get(), folder_.c_str(), events_ | kSelf | IN_ONLYDIR);
        if (folderWd_ >= 0) {
            problem_.clear();
            return;
        }
        const int error = errno;
        if (error != ENOENT && error != ENOTDIR) { // there, but not ours to watch (EACCES, no watches left)
            problem_ = "cannot watch the folder " + folder_ + ": " + std::strerror(error);
            return;
        }
        if (waitInAncestor(error))
            return;
    }
}

bool FolderWatch::waitInAncestor(int folderErrno)
{
    std::filesystem::path step(folder_), ancestor = step.parent_path();
    while (!ancestor.empty() && !isFolder(ancestor) && ancestor != ancestor.parent_path()) {
        step = ancestor;
        ancestor = ancestor.parent_path();
    }
    if (ancestor.empty())
        ancestor = "."; // a relative folder's first step
    ancestorWd_ = ::inotify_add_watch(fd_.get(), ancestor.c_str(), kAppears | kSelf | IN_ONLYDIR);
    if (ancestorWd_ < 0) {
        const int error = errno;
        if (!isFolder(ancestor))
            return false; // removed meanwhile: look further up
        problem_ = "the folder " + folder_ + " is gone, and " + ancestor.string() +
                   " cannot be watched for it: " + std::strerror(error);
        return true;
    }
    problem_ = "the folder " + folder_ + " is gone (" + std::strerror(folderErrno) + "): waiting for it in " +
               ancestor.string();
    // A step made between our look and our watch sent no event to wait for: look again.
    return !isFolder(step);
}

void FolderWatch::drop(int &wd)
{
    if (wd >= 0)
        (void)::inotify_rm_watch(fd_.get(), wd); // EINVAL when the kernel dropped it already (IN_IGNORED)
    wd = -1;
}

} // namespace overlayd
