// SinkFile: a FIFO without a reader never blocks the open (it starts at the first frame after a reader came, header
// first), and a file another writer holds is refused naming the process.
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

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
