// SPDX-License-Identifier: Apache-2.0
// readRegularFile: stat, open non-blocking, fstat again (the path may have changed in between), read at most one byte
// more than allowed.
#include "base/regular_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace overlayd {

namespace {

Error fromErrno(const char *what, int error)
{
    if (error == ENOENT || error == ENOTDIR)
        return makeError(ErrorCode::NotFound, "does not exist");
    return makeError(ErrorCode::Io, std::string(what) + ": " + std::strerror(error));
}

Status checkKind(const struct stat &info, size_t maxBytes)
{
    if (!S_ISREG(info.st_mode))
        return makeError(ErrorCode::InvalidArgument,
                         std::string("is ") + fileKindName(unsigned(info.st_mode)) + ", not a regular file");
    if (uintmax_t(info.st_size) > maxBytes)
        return makeError(ErrorCode::InvalidArgument, "has " + std::to_string(info.st_size) + " bytes; at most " +
                                                         std::to_string(maxBytes) + " are read");
    return Ok{};
}

template<typename Bytes>
Result<Bytes> readLimited(const std::string &path, size_t maxBytes)
{
    auto file = openRegularFile(path, maxBytes);
    if (!file)
        return file.error();
    const UniqueFd &fd = file->fd;
    Bytes bytes(size_t(file->size) + 1, 0); // one byte more than stat says: a file that grew is seen
    size_t have = 0;
    for (;;) {
        if (have == bytes.size()) {
            if (bytes.size() > maxBytes)
                return makeError(ErrorCode::InvalidArgument,
                                 "grew past " + std::to_string(maxBytes) + " bytes while it was read");
            bytes.resize(std::min(bytes.size() * 2, maxBytes < SIZE_MAX ? maxBytes + 1 : maxBytes));
        }
        const ssize_t got = ::read(fd.get(), bytes.data() + have, bytes.size() - have);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            return fromErrno("cannot be read", errno);
        if (got == 0)
            break;
        have += size_t(got);
    }
    bytes.resize(have);
    return bytes;
}

} // namespace

Result<RegularFile> openRegularFile(const std::string &path, size_t maxBytes)
{
    // stat() first: a device is refused without being opened (opening some has side effects).
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0)
        return fromErrno("cannot be read", errno);
    if (auto kind = checkKind(info, maxBytes); !kind)
        return kind.error();
    UniqueFd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    if (!fd.isValid())
        return fromErrno("cannot be opened", errno);
    if (::fstat(fd.get(), &info) != 0) // the path may name something else by now
        return fromErrno("cannot be read", errno);
    if (auto kind = checkKind(info, maxBytes); !kind)
        return kind.error();
    return RegularFile{std::move(fd), uint64_t(info.st_size)};
}

const char *fileKindName(unsigned mode)
{
    switch (mode & S_IFMT) {
    case S_IFREG:
        return "a regular file";
    case S_IFDIR:
        return "a directory";
    case S_IFCHR:
        return "a character device";
    case S_IFBLK:
        return "a block device";
    case S_IFIFO:
        return "a FIFO";
    case S_IFSOCK:
        return "a socket";
    case S_IFLNK:
        return "a symbolic link";
    default:
        return "an unknown kind of file";
    }
}

Result<std::string> readRegularFile(const std::string &path, size_t maxBytes)
{
    return readLimited<std::string>(path, maxBytes);
}

Result<std::vector<uint8_t>> readRegularFileBytes(const std::string &path, size_t maxBytes)
{
    return readLimited<std::vector<uint8_t>>(path, maxBytes);
}

} // namespace overlayd
