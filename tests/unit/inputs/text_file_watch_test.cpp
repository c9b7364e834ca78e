// SPDX-License-Identifier: Apache-2.0
// TextFileWatch on real files: each way a program writes a file is seen, other files in the folder are not, and
// slotLine keeps one clean line within its byte limit.
#include "inputs/text_file_watch.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <poll.h>
#include <sys/stat.h>
#include <thread>

#include <gtest/gtest.h>
#include <unistd.h>

using namespace overlayd;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string &name)
{
    // One folder per process: two builds' test runs on one machine must not write into each other's folder.
    const fs::path dir = fs::temp_directory_path() / ("overlayd-text-watch-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Whether the watch reports its file within a second (events for other files are consumed and not counted).
bool reportsChange(TextFileWatch &watch)
{
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{watch.fd(), POLLIN, 0};
        if (::poll(&p, 1, 100) > 0 && watch.consume())
            return true;
    }
    return false;
}

} // namespace

TEST(SlotLine, KeepsTheFirstLineWithoutControlCharactersWithinTheLimit)
{
    EXPECT_EQ(slotLine("reversing\nsecond line\n", 256), "reversing");
    EXPECT_EQ(slotLine("a\tb\rc\x7f"
                       "d\x01",
                       256),
              "abcd");
    EXPECT_EQ(slotLine("", 256), "");
    EXPECT_EQ(slotLine("abcdef", 4), "abcd");
    // "é" is two bytes (C3 A9): a cut inside it drops the whole character, never half of it.
    EXPECT_EQ(slotLine("ab\xC3\xA9", 3), "ab");
    EXPECT_EQ(slotLine("ab\xC3\xA9", 4), "ab\xC3\xA9");
    // A three-byte character (the euro sign, E2 82 AC) cut after one or two of its bytes.
    EXPECT_EQ(slotLine("x\xE2\x82\xAC", 2), "x");
    EXPECT_EQ(slotLine("x\xE2\x82\xAC", 3), "x");
}

TEST(TextFileWatch, FollowsWritesRenamesAndDeletesOfItsFileOnly)
{
    const fs::path dir = scratch("follow");
    const std::string path = (dir / "status.txt").string();
    auto watch = TextFileWatch::open(path, 16);
    ASSERT_TRUE(watch.ok()) << watch.error().message;
    EXPECT_EQ(watch->read(), ""); // not there yet

    std::ofstream(path) << "parked\n";
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "parked");

    std::ofstream(dir / "other.txt") << "not ours\n";
    EXPECT_FALSE(reportsChange(*watch));

    std::ofstream(dir / "status.tmp") << "reversing, and a line longer than sixteen bytes\n";
    EXPECT_FALSE(reportsChange(*watch)); // the temporary file is not the one watched
    fs::rename(dir / "status.tmp", path);
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "reversing, and a");

    fs::remove(path);
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "");
}

TEST(TextFileWatch, AMissingFolderIsRefusedNamingIt)
{
    auto watch = TextFileWatch::open("/nonexistent-overlayd-folder/status.txt", 16);
    ASSERT_FALSE(watch.ok());
    EXPECT_NE(watch.error().message.find("/nonexistent-overlayd-folder"), std::string::npos);
}

// What is at the path must be a file to be watched as one: a directory, a FIFO or a device is refused (the config
// loader asks the same question); nothing there yet, or a regular file, is fine.
TEST(TextFileWatch, RefusesAPathThatIsNotARegularFile)
{
    const fs::path dir = scratch("kinds");
    const std::string fifo = (dir / "pipe").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::ofstream(dir / "status.txt") << "ok\n";
    EXPECT_NE(watchedFileProblem(fifo).find("is a FIFO"), std::string::npos) << watchedFileProblem(fifo);
    EXPECT_NE(watchedFileProblem(dir.string()).find("is a directory"), std::string::npos);
    EXPECT_NE(watchedFileProblem("/dev/null").find("is a character device"), std::string::npos);
    EXPECT_EQ(watchedFileProblem((dir / "status.txt").string()), "");
    EXPECT_EQ(watchedFileProblem((dir / "later.txt").string()), "");
    EXPECT_FALSE(TextFileWatch::open(fifo, 16).ok());
    EXPECT_TRUE(TextFileWatch::open((dir / "later.txt").string(), 16).ok());
    fs::remove_all(dir);
}
