// SPDX-License-Identifier: Apache-2.0
#include "inputs/text_file_watch.h"

#include <fcntl.h>
#include <filesystem>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/regular_file.h"
#include "base/utf8.h"

namespace overlayd {

namespace {

// What a writer does: write and close, rename over, create, delete, or keep writing an open file.
constexpr uint32_t kEveryWrite = IN_CLOSE_WRITE | IN_MODIFY | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MOVED_FROM;
// Only a complete version: closed after writing, renamed in, or gone.
constexpr uint32_t kWhenComplete = IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE | IN_MOVED_FROM;

} // namespace

std::string slotLine(std::string_view content, size_t maxBytes)
{
    std::string line;
    for (const char c : content) {
        if (c == '\n')
            break;
        if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f)
            line += c;
    }
    line.resize(utf8Cut(line, maxBytes));
    return line;
}

std::string watchedFileProblem(const std::string &path)
{
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0 || S_ISREG(info.st_mode))
        return {};
    return "'" + path + "' is " + fileKindName(info.st_mode) +
           ": a watched file must be a regular file (or not exist yet: it may appear later)";
}

Result<TextFileWatch> TextFileWatch::open(const std::string &path, size_t maxBytes, Reread reread)
{
    if (const std::string problem = watchedFileProblem(path); !problem.empty())
        return makeError(ErrorCode::InvalidArgument, problem);
    const std::filesystem::path file(path);
    const std::string folder = file.parent_path().empty() ? "." : file.parent_path().string();
    auto watch = FolderWatch::open(folder, reread == Reread::EveryWrite ? kEveryWrite : kWhenComplete);
    if (!watch)
        return makeError(watch.error().code, watch.error().message + " (of " + path + ")");
    return TextFileWatch(std::move(*watch), path, file.filename().string(), maxBytes);
}

std::string TextFileWatch::read() const
{
    // Enough for the longest line a slot shows plus what slotLine drops; the rest of the file is never read.
    return slotLine(readPrefix(maxBytes_ * 4 + 63), maxBytes_);
}

std::string TextFileWatch::readPrefix(size_t maxBytes) const
{
    UniqueFd fd(::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (fd.get() < 0)
        return {};
    std::string content(maxBytes + 1, '\0');
    size_t have = 0;
    while (have < content.size()) { // a regular file may return less than asked before its end
        const ssize_t got = ::read(fd.get(), content.data() + have, content.size() - have);
        if (got <= 0)
            break;
        have += size_t(got);
    }
    content.resize(have);
    return content;
}

} // namespace overlayd
