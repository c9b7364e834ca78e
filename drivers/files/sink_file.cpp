// SPDX-License-Identifier: Apache-2.0
// SinkFile: O_NONBLOCK opens (a FIFO without a reader answers ENXIO at once), the lock, then a blocking FILE.
#include "drivers/files/sink_file.h"

#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/unique_fd.h"
#include "drivers/files/file_lock.h"

namespace overlayd {

namespace {

Error openError(const std::string &path, const char *what)
{
    return makeError(errno == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                     path + ": " + what + ": " + std::strerror(errno));
}

} // namespace

Status SinkFile::open(bool append, std::string prologue)
{
    if (append && fifo_ && file_) { // the parked FIFO: its reader reads on
        wanted_ = true;
        return Ok{};
    }
    (void)closeFile();
    wanted_ = true;
    append_ = append;
    // A FIFO still waiting for its reader has not written the last prologue yet: it comes first.
    if (!append) {
        prologue_.clear();
        readerPrologue_ = prologue;
    }
    prologue_ += prologue;
    const Status opened = tryOpen();
    if (!opened && opened.error().code == ErrorCode::TryAgain)
        return Ok{}; // a FIFO without a reader yet: get() tries again with each frame
    if (!opened)
        wanted_ = false;
    return opened;
}

Status SinkFile::tryOpen()
{
    makeParentFolders(path_);
    // No O_TRUNC: the file is emptied only once the lock says it is ours (a second daemon must not wipe the first's
    // output on its way to being refused).
    UniqueFd fd(::open(path_.c_str(), O_WRONLY | O_CREAT | O_NONBLOCK | O_CLOEXEC | (append_ ? O_APPEND : 0), 0666));
    if (!fd.isValid())
        return errno == ENXIO ? makeError(ErrorCode::TryAgain, path_ + ": a FIFO that nobody reads yet")
                              : openError(path_, "cannot create");
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0)
        return openError(path_, "cannot stat");
    fifo_ = S_ISFIFO(info.st_mode);
    if (S_ISREG(info.st_mode)) {
        if (auto locked = lockExclusive(fd.get(), path_); !locked)
            return locked;
        if (!append_ && ::ftruncate(fd.get(), 0) != 0)
            return openError(path_, "cannot truncate");
    }
    // From here writes may block like any file's: the sink's own thread waits, and its queue drops for it.
    if (::fcntl(fd.get(), F_SETFL, ::fcntl(fd.get(), F_GETFL) & ~O_NONBLOCK) != 0)
        return openError(path_, "fcntl");
    UniqueFile file(::fdopen(fd.get(), append_ ? "ab" : "wb"));
    if (!file)
        return openError(path_, "fdopen");
    (void)fd.release(); // the FILE owns it now
    file_ = std::move(file);
    const std::string prologue = std::exchange(prologue_, {});
    return writeAll(file_.get(), prologue.data(), prologue.size(), path_);
}

Result<std::FILE *> SinkFile::get()
{
    if (!wanted_)
        return makeError(ErrorCode::InvalidArgument, path_ + " is not open");
    if (!file_) {
        if (auto opened = tryOpen(); !opened)
            return opened.error().code == ErrorCode::TryAgain
                       ? makeError(ErrorCode::Io, path_ + ": no reader on the FIFO yet: frame not written")
                       : opened.error();
    }
    return file_.get();
}

Status SinkFile::write(const void *data, size_t size)
{
    auto out = get();
    if (!out)
        return out.error();
    if (size == 0 || std::fwrite(data, 1, size, *out) == size)
        return Ok{};
    const int error = errno;
    if (!fifo_ || error != EPIPE)
        return makeError(ErrorCode::Io, path_ + ": write failed: " + std::strerror(error));
    // Writing on would hand the next reader a stream cut mid-frame and without its header: start it afresh.
    readerGone();
    return makeError(ErrorCode::Io, path_ + ": the FIFO's reader went away: frame not written (a new reader gets the "
                                            "stream from its header)");
}

void SinkFile::readerGone()
{
    file_.reset();
    prologue_ = readerPrologue_;
}

Status SinkFile::close()
{
    wanted_ = false;
    if (!fifo_ || !file_)
        return closeFile();
    if (std::fflush(file_.get()) == 0)
        return Ok{};
    const int error = errno;
    // Any other failure lost bytes of the reader's stream: reported as a failed write() is.
    if (error != EPIPE)
        return makeError(ErrorCode::Io, path_ + ": write failed on close: " + std::strerror(error));
    readerGone();
    return Ok{}; // a FIFO's reader that left is no failure of the stream
}

Status SinkFile::closeFile()
{
    if (file_ && std::fclose(file_.release()) != 0)
        return makeError(ErrorCode::Io, path_ + ": write failed on close");
    return Ok{};
}

} // namespace overlayd
