// SPDX-License-Identifier: Apache-2.0
// The recorder's directory through POSIX: readdir + fstatat without following links, rename(2), statvfs(3), and a
// probe file made with mkstemp, since permission bits alone do not tell (root, read-only mounts, full quotas).
#include "stream/directory_segment_store.h"

#include <cerrno>
#include <cstring>
#include <memory>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace overlayd {

namespace {

struct DirCloser {
    void operator()(DIR *dir) const { closedir(dir); }
};

Error ioError(const std::string &what, int error)
{
    return makeError(ErrorCode::Io, what + ": " + std::strerror(error));
}

} // namespace

DirectorySegmentStore::DirectorySegmentStore(std::string directory) : directory_(std::move(directory))
{
    while (directory_.size() > 1 && directory_.back() == '/')
        directory_.pop_back();
}

Result<std::vector<SegmentStore::Entry>> DirectorySegmentStore::list()
{
    const std::unique_ptr<DIR, DirCloser> dir(opendir(directory_.c_str()));
    if (!dir)
        return ioError("'" + directory_ + "'", errno);
    std::vector<Entry> entries;
    while (const dirent *entry = readdir(dir.get())) {
        struct stat info {};
        if (fstatat(dirfd(dir.get()), entry->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(info.st_mode))
            continue; // gone since readdir, or not a file the recorder could have written
        entries.push_back({entry->d_name, uint64_t(info.st_size)});
    }
    return entries;
}

Status DirectorySegmentStore::remove(const std::string &name)
{
    if (unlink(pathOf(name).c_str()) != 0)
        return ioError("removing '" + pathOf(name) + "'", errno);
    return Ok{};
}

Status DirectorySegmentStore::rename(const std::string &from, const std::string &to)
{
    if (::rename(pathOf(from).c_str(), pathOf(to).c_str()) != 0)
        return ioError("renaming '" + pathOf(from) + "' to '" + to + "'", errno);
    return Ok{};
}

Result<uint64_t> DirectorySegmentStore::freeBytes()
{
    struct statvfs info {};
    if (statvfs(directory_.c_str(), &info) != 0)
        return ioError("'" + directory_ + "'", errno);
    return uint64_t(info.f_bavail) * uint64_t(info.f_frsize);
}

Status DirectorySegmentStore::checkWritable()
{
    struct stat info {};
    if (stat(directory_.c_str(), &info) != 0)
        return makeError(errno == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                         "'" + directory_ + "' " + (errno == ENOENT ? "does not exist" : std::strerror(errno)));
    if (!S_ISDIR(info.st_mode))
        return makeError(ErrorCode::InvalidArgument, "'" + directory_ + "' is not a directory");
    std::string probe = pathOf(".overlayd-write-check-XXXXXX");
    const int fd = mkstemp(probe.data());
    if (fd < 0)
        return ioError("'" + directory_ + "' is not writable", errno);
    close(fd);
    unlink(probe.c_str());
    return Ok{};
}

} // namespace overlayd
