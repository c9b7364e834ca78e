// SPDX-License-Identifier: Apache-2.0
// SinkFile: a FIFO without a reader never blocks the open (it starts at the first frame after a reader came, header
// first), a reader that goes away is followed by the next one from the header on, and a file another writer holds is
// refused naming the process.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "base/unique_fd.h"
#include "drivers/files/sink_file.h"

namespace overlayd {
namespace {

namespace fs = std::filesystem;

// A fresh folder, removed at the end of the test. The pid in its name: another build's tests may run at the same
// time on the machine.
struct Scratch {
    explicit Scratch(const std::string &name)
        : dir(fs::path(::testing::TempDir()) / ("overlayd-sink-file-" + name + "-" + std::to_string(::getpid())))
    {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Scratch() { fs::remove_all(dir); }
    std::string operator/(const std::string &file) const { return (dir / file).string(); }
    fs::path dir;
};

// A FIFO in a fresh folder, a SinkFile opened on it with a header, and a reader that came after the open. The
// reader is declared before the file so that it outlives it (a writer closing after its reader left gets SIGPIPE).
struct ReadFifo {
    explicit ReadFifo(const std::string &name) : scratch(name), path(scratch / "out.y4m"), file(path)
    {
        EXPECT_EQ(mkfifo(path.c_str(), 0644), 0);
        EXPECT_TRUE(file.open(false, "HEADER\n"));
        readerFd = UniqueFd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
        reader = readerFd.get();
    }

    const Scratch scratch;
    const std::string path;
    UniqueFd readerFd;
    SinkFile file;
    int reader = -1;
};

TEST(SinkFile, AFifoWithoutAReaderOpensOnceOneComes)
{
    const Scratch scratch("fifo");
    const std::string path = scratch / "out.y4m";
    ASSERT_EQ(mkfifo(path.c_str(), 0644), 0);
    SinkFile file(path);
    ASSERT_TRUE(file.open(false, "HEADER\n")); // returns at once: nobody reads yet
    const auto early = file.get();
    ASSERT_FALSE(early);
    EXPECT_NE(early.error().message.find("no reader"), std::string::npos) << early.error().message;

    const int reader = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    const auto late = file.get();
    ASSERT_TRUE(late) << late.error().message;
    ASSERT_EQ(std::fflush(*late), 0);
    char text[8] = {};
    EXPECT_EQ(::read(reader, text, 7), 7);
    EXPECT_STREQ(text, "HEADER\n");
    EXPECT_TRUE(file.close());
    ::close(reader);
}

// A FIFO's reader leaves mid-stream (ffplay closed) and another comes: the second must get a stream it can read,
// the header first, not the rest of the first reader's stream. (Found by the soak test: readers after the first got
// frames without a Y4M header.)
TEST(SinkFile, TheNextReaderOfAFifoGetsTheHeaderFirst)
{
    const Scratch scratch("fifo-readers");
    const std::string path = scratch / "out.y4m";
    ASSERT_EQ(mkfifo(path.c_str(), 0644), 0);
    const auto previous = std::signal(SIGPIPE, SIG_IGN); // as the daemon does: a gone reader is EPIPE, not a signal
    // Larger than stdio's buffer (each write reaches the pipe at once), smaller than the pipe (it never blocks).
    const std::vector<char> frame(16384, 'F');
    SinkFile file(path);
    ASSERT_TRUE(file.open(false, "HEADER\n"));

    const int first = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(first, 0);
    ASSERT_TRUE(file.write(frame.data(), frame.size()));
    ASSERT_EQ(std::fflush(*file.get()), 0); // stdio may hold the last few bytes
    std::vector<char> seen(frame.size() + 7);
    EXPECT_EQ(::read(first, seen.data(), seen.size()), ssize_t(seen.size()));
    ::close(first);

    const Status gone = file.write(frame.data(), frame.size());
    ASSERT_FALSE(gone);
    EXPECT_NE(gone.error().message.find("reader went away"), std::string::npos) << gone.error().message;

    const int second = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(second, 0);
    ASSERT_TRUE(file.write(frame.data(), frame.size()));
    ASSERT_EQ(std::fflush(*file.get()), 0);
    std::fill(seen.begin(), seen.end(), 0);
    EXPECT_EQ(::read(second, seen.data(), seen.size()), ssize_t(seen.size()));
    EXPECT_EQ(std::string(seen.data(), 7), "HEADER\n");
    EXPECT_EQ(seen.back(), 'F');
    EXPECT_TRUE(file.close());
    ::close(second);
    std::signal(SIGPIPE, previous);
}

// A sink re-opened for the same stream (a reload, the camera re-opened) keeps its FIFO: closing it would give the
// reader end of file (ffplay quits), and re-opening would give a reader that came meanwhile no header.
TEST(SinkFile, AReopenForTheSameStreamKeepsTheFifosReader)
{
    ReadFifo fifo("fifo-reopen");
    SinkFile &file = fifo.file;
    const int reader = fifo.reader;
    ASSERT_GE(reader, 0);
    ASSERT_TRUE(file.write("one\n", 4));
    ASSERT_TRUE(file.close());
    char text[16] = {};
    EXPECT_EQ(::read(reader, text, sizeof text), 11);
    EXPECT_STREQ(text, "HEADER\none\n");
    errno = 0;
    EXPECT_EQ(::read(reader, text, sizeof text), -1) << "end of file: the writer went away";
    EXPECT_EQ(errno, EAGAIN);

    ASSERT_TRUE(file.open(true));
    ASSERT_TRUE(file.write("two\n", 4));
    ASSERT_EQ(std::fflush(*file.get()), 0);
    std::fill(std::begin(text), std::end(text), 0);
    EXPECT_EQ(::read(reader, text, sizeof text), 4);
    EXPECT_STREQ(text, "two\n");
}

// Parking a FIFO flushes it; a flush that fails for any reason but a reader gone (EPIPE) lost bytes of the stream and
// must be reported like a failed write. The failure is made by putting a read-only descriptor under the FILE.
TEST(SinkFile, AParkedFifosFailedFlushIsReported)
{
    ReadFifo fifo("fifo-flush");
    SinkFile &file = fifo.file;
    ASSERT_GE(fifo.reader, 0);
    ASSERT_TRUE(file.write("one\n", 4)); // stays in stdio's buffer
    const auto out = file.get();
    ASSERT_TRUE(out);
    const int readOnly = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    ASSERT_GE(readOnly, 0);
    ASSERT_GE(::dup2(readOnly, ::fileno(*out)), 0); // the flush's write(2) now fails with EBADF
    ::close(readOnly);
    const Status closed = file.close();
    ASSERT_FALSE(closed) << "a lost write must not pass as a parked FIFO";
    EXPECT_NE(closed.error().message.find("write failed on close"), std::string::npos) << closed.error().message;
    EXPECT_NE(closed.error().message.find(fifo.path), std::string::npos) << closed.error().message;
}

// Two writers on one file (here in one process; another daemon alike): the second is refused naming the holder,
// and finds the first's bytes untouched (nothing is truncated before the lock is ours).
TEST(SinkFile, ALockedFileIsRefusedNamingItsHolder)
{
    const Scratch scratch("lock");
    const std::string path = scratch / "out.raw";
    SinkFile first(path);
    ASSERT_TRUE(first.open(false, "FIRST"));
    ASSERT_EQ(std::fflush(*first.get()), 0);
    SinkFile second(path);
    const Status refused = second.open(false, "SECOND");
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("locked by process " + std::to_string(getpid())), std::string::npos)
        << refused.error().message;
    EXPECT_EQ(fs::file_size(path), 5u);
    EXPECT_TRUE(first.close());
    EXPECT_TRUE(second.open(false, "SECOND")) << "the lock goes with the close";
    EXPECT_TRUE(second.close());
    EXPECT_EQ(fs::file_size(path), 6u);
}

} // namespace
} // namespace overlayd
