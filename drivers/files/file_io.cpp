// stdio with errors as Results.
#include "drivers/files/file_io.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

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
    UniqueFile file(std::fopen(path.c_str(), "rb"));
    if (!file)
        return ioError("cannot open", path, errno);
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
    auto file = openForReading(path);
    if (!file)
        return file.error();
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(path, error);
    if (error)
        return makeError(ErrorCode::Io, path + ": cannot read its size: " + error.message());
    if (size > maxBytes)
        return makeError(ErrorCode::Malformed, path + " has " + std::to_string(size) + " bytes; at most " +
                                                   std::to_string(maxBytes) + " are read");
    std::vector<uint8_t> bytes(size);
    auto got = readUpTo(file->get(), bytes.data(), bytes.size(), path);
    if (!got)
        return got.error();
    bytes.resize(*got);
    return bytes;
}

Status writeAll(std::FILE *file, const void *data, size_t size, const std::string &path)
{
    if (size != 0 && std::fwrite(data, 1, size, file) != size)
        return ioError("write failed", path, errno);
    return Ok{};
}

Status replaceFile(const std::string &path, const void *data, size_t size)
{
    const std::string temporary = path + ".tmp";
    {
        auto file = openForWriting(temporary, false);
        if (!file)
            return file.error();
        if (auto written = writeAll(file->get(), data, size, temporary); !written)
            return written;
        if (std::fclose(file->release()) != 0)
            return ioError("write failed", temporary, errno);
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
        return ioError("cannot rename into place", path, errno);
    return Ok{};
}

} // namespace overlayd
