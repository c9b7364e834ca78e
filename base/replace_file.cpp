// SPDX-License-Identifier: Apache-2.0
// The temporary's name is random (getrandom), so that a file or link planted at a predictable "NAME.tmp" can neither
// redirect the write (O_NOFOLLOW, O_EXCL) nor make it fail; renameat within one folder is atomic.
#include "base/replace_file.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/random.h>
#include <unistd.h>

#include "base/unique_fd.h"

namespace overlayd {

namespace {

// How many random names are tried before giving up (each collision needs 64 matching random bits).
constexpr int kTemporaryNameAttempts = 8;

Error ioError(const std::string &what, const std::string &path, int error)
{
    return makeError(ErrorCode::Io, what + " " + path + ": " + std::strerror(error));
}

std::string randomSuffix()
{
    uint64_t bits = 0;
    if (getrandom(&bits, sizeof(bits), 0) != ssize_t(sizeof(bits)))
        bits = uint64_t(getpid()) * 0x9e3779b97f4a7c15ull ^ uint64_t(reinterpret_cast<uintptr_t>(&bits));
    static constexpr char kHex[] = "0123456789abcdef";
    std::string text(16, '0');
    for (char &c : text) {
        c = kHex[bits & 15];
        bits >>= 4;
    }
    return text;
}

Status writeWhole(int fd, std::string_view text, const std::string &name, Durability durability)
{
    while (!text.empty()) {
        const ssize_t written = ::write(fd, text.data(), text.size());
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0)
            return ioError("cannot write", name, written < 0 ? errno : EIO);
        text.remove_prefix(size_t(written));
    }
    if (durability == Durability::Synced && ::fsync(fd) != 0)
        return ioError("cannot sync", name, errno);
    return Ok{};
}

} // namespace

Status replaceFileContents(const std::string &path, std::string_view text, Durability durability)
{
    const std::filesystem::path target(path);
    const std::string folderName = target.has_parent_path() ? target.parent_path().string() : ".";
    const std::string fileName = target.filename().string();
    UniqueFd folder(::open(folderName.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (folder.get() < 0)
        return ioError("cannot open the folder", folderName, errno);
    std::string temporary;
    UniqueFd file;
    for (int attempt = 0; attempt < kTemporaryNameAttempts && file.get() < 0; ++attempt) {
        temporary = "." + fileName + "." + randomSuffix() + ".tmp";
        file = UniqueFd(
            ::openat(folder.get(), temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
        if (file.get() < 0 && errno != EEXIST)
            break;
    }
    const std::string temporaryPath = (std::filesystem::path(folderName) / temporary).string();
    if (file.get() < 0)
        return ioError("cannot create", temporaryPath, errno);
    Status status = writeWhole(file.get(), text, temporaryPath, durability);
    if (status && ::close(file.release()) != 0)
        status = ioError("cannot write", temporaryPath, errno);
    if (status && ::renameat(folder.get(), temporary.c_str(), folder.get(), fileName.c_str()) != 0)
        status = ioError("cannot rename into place", path, errno);
    if (!status) {
        ::unlinkat(folder.get(), temporary.c_str(), 0);
        return status;
    }
    // The rename is durable once the folder's entry is: without this a crash may bring back the old file.
    if (durability == Durability::Synced && ::fsync(folder.get()) != 0)
        return ioError("cannot sync the folder", folderName, errno);
    return Ok{};
}

} // namespace overlayd
