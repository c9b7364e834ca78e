// SPDX-License-Identifier: Apache-2.0
// stdio with errors as Results.
#include "drivers/files/file_io.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "base/regular_file.h"

namespace overlayd {

namespace {

Error ioError(const std::string &what, const std::string &path, int error)
{
    return makeError(error == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                     path + ": " + what + ": " + std::strerror(error));
}

} // namespace

void makeParentFolders(const std::string &path)
{
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ignored; // opening the file reports what matters
    if (!parent.empty())
        std::filesystem::create_directories(parent, ignored);
}

Result<UniqueFile> openForReading(const std::string &path)
{
    // Not fopen: a FIFO with no writer would block it, and a directory would open and fail at the first read.
    auto regular = openRegularFile(path);
    if (!regular)
        return makeError(regular.error().code, path + ": " + regular.error().message);
    UniqueFile file(::fdopen(regular->fd.get(), "rb"));
    if (!file)
        return ioError("cannot open", path, errno);
    (void)regular->fd.release(); // the FILE owns it now
    return file;
}

Result<UniqueFile> openForWriting(const std::string &path, bool append)
{
    makeParentFolders(path);
    UniqueFile file(std::fopen(path.c_str(), append ? "ab" : "wb"));
    if (!file)
        return ioError("cannot create", path, errno);
    return file;
}

Result<size_t> readUpTo(std::FILE *file, void *data, size_t size, const std::string &path)
{
    if (size == 0) // an empty plane (a luma-only frame's chroma) has no buffer: fread(nullptr) is undefined
        return size_t(0);
    const size_t got = std::fread(data, 1, size, file);
    if (got < size && std::ferror(file))
        return ioError("read failed", path, errno);
    return got;
}

Result<std::vector<uint8_t>> readWholeFile(const std::string &path, uintmax_t maxBytes)
{
    auto bytes = readRegularFileBytes(path, size_t(maxBytes));
    if (!bytes)
        return makeError(bytes.error().code == ErrorCode::InvalidArgument ? ErrorCode::Malformed : bytes.error().code,
                         path + ": " + bytes.error().message);
    return bytes;
}

Status writeAll(std::FILE *file, const void *data, size_t size, const std::string &path)
{
    if (size != 0 && std::fwrite(data, 1, size, file) != size)
        return ioError("write failed", path, errno);
    return Ok{};
}

} // namespace overlayd
