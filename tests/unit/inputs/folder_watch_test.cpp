// SPDX-License-Identifier: Apache-2.0
// A watched file's folder followed by its path, on real folders: removed and made again (what systemd does to a
// service's RuntimeDirectory= on every restart), several times, with its parent, moved away, and the file then
// replaced by rename; each time the watch must report the new file's writes, and say while it waits.
#include "inputs/folder_watch.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "inputs/text_file_watch.h"

using namespace overlayd;
namespace fs = std::filesystem;

namespace {

// One folder per test and process: CTest runs the tests of this file in parallel.
fs::path scratch()
{
    const fs::path dir = fs::temp_directory_path() / (std::string("overlayd-folder-watch-") +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                                                      "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Whether the watch reports its file within `wait` (events for other files are consumed and not counted).
bool reportsChange(TextFileWatch &watch, std::chrono::milliseconds wait = std::chrono::milliseconds(1000))
{
    const auto deadline = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{watch.fd(), POLLIN, 0};
        if (::poll(&p, 1, 20) > 0 && watch.consume())
            return true;
    }
    return false;
}

// Lets the watch read what the folder's removal or return sent, whatever it reports.
void settle(TextFileWatch &watch)
{
    while (reportsChange(watch, std::chrono::milliseconds(100))) {
    }
}

void write(const fs::path &file, const std::string &text)
{
    std::ofstream(file) << text << "\n";
}

} // namespace

TEST(FolderWatch, AFolderRemovedAndMadeAgainIsFollowedEachTime)
{
    const fs::path dir = scratch() / "run";
    fs::create_directories(dir);
    auto watch = TextFileWatch::open((dir / "status.txt").string(), 64);
    ASSERT_TRUE(watch.ok()) << watch.error().message;
    write(dir / "status.txt", "first");
    ASSERT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "first");

    for (int restart = 1; restart <= 3; ++restart) {
        fs::remove_all(dir);
        settle(*watch);
        EXPECT_EQ(watch->read(), "");
        fs::create_directories(dir);
        settle(*watch);
        const std::string text = "after restart " + std::to_string(restart);
        write(dir / "status.txt", text);
        EXPECT_TRUE(reportsChange(*watch)) << "restart " << restart << ": the new folder's file is not followed";
        EXPECT_EQ(watch->read(), text);
    }
}

TEST(FolderWatch, AFolderRemovedWithItsParentIsFollowedWhenBothAreBack)
{
    const fs::path base = scratch(), dir = base / "parent" / "run";
    fs::create_directories(dir);
    auto watch = TextFileWatch::open((dir / "status.txt").string(), 64);
    ASSERT_TRUE(watch.ok()) << watch.error().message;

    // mkdir -p: both folders at once, the second perhaps before the first is watched.
    fs::remove_all(base / "parent");
    settle(*watch);
    fs::create_directories(dir);
    settle(*watch);
    write(dir / "status.txt", "both at once");
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "both at once");

    // One by one, with time between: the watch moves down the path a step at a time.
    fs::remove_all(base / "parent");
    settle(*watch);
    fs::create_directory(base / "parent");
    settle(*watch);
    fs::create_directory(dir);
    settle(*watch);
    write(dir / "status.txt", "one by one");
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "one by one");
}

TEST(FolderWatch, AFileReplacedByRenameInTheNewFolderIsFollowed)
{
    const fs::path dir = scratch() / "run";
    fs::create_directories(dir);
    auto watch = TextFileWatch::open((dir / "status.txt").string(), 64, TextFileWatch::Reread::WhenComplete);
    ASSERT_TRUE(watch.ok()) << watch.error().message;
    fs::remove_all(dir);
    settle(*watch);
    fs::create_directories(dir);
    settle(*watch);

    write(dir / "status.tmp", "renamed in");
    EXPECT_FALSE(reportsChange(*watch, std::chrono::milliseconds(200))); // not the watched name
    fs::rename(dir / "status.tmp", dir / "status.txt");
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "renamed in");
}

TEST(FolderWatch, AFolderMovedAwayIsLeftAndTheOneAtItsPathFollowed)
{
    const fs::path base = scratch(), dir = base / "run";
    fs::create_directories(dir);
    auto watch = TextFileWatch::open((dir / "status.txt").string(), 64);
    ASSERT_TRUE(watch.ok()) << watch.error().message;
    write(dir / "status.txt", "old");
    ASSERT_TRUE(reportsChange(*watch));

    fs::rename(dir, base / "run.old");
    settle(*watch);
    fs::create_directories(dir);
    settle(*watch);
    write(base / "run.old" / "status.txt", "in the moved folder");
    EXPECT_FALSE(reportsChange(*watch, std::chrono::milliseconds(200)));
    write(dir / "status.txt", "new");
    EXPECT_TRUE(reportsChange(*watch));
    EXPECT_EQ(watch->read(), "new");
}

TEST(FolderWatch, SaysWhatItWaitsForWhileTheFolderIsGone)
{
    const fs::path base = scratch(), dir = base / "parent" / "run";
    fs::create_directories(dir);
    auto watch = FolderWatch::open(dir.string(), IN_CLOSE_WRITE);
    ASSERT_TRUE(watch.ok()) << watch.error().message;
    EXPECT_TRUE(watch->following());
    EXPECT_EQ(watch->problem(), "");

    fs::remove_all(base / "parent");
    pollfd p{watch->fd(), POLLIN, 0};
    ASSERT_EQ(::poll(&p, 1, 1000), 1);
    EXPECT_TRUE(watch->consume("status.txt")); // the file it held is gone with it
    EXPECT_FALSE(watch->following());
    EXPECT_EQ(watch->problem(), "the folder " + dir.string() +
                                    " is gone (No such file or directory): waiting for it in " + base.string());

    fs::create_directories(dir);
    ASSERT_EQ(::poll(&p, 1, 1000), 1);
    EXPECT_TRUE(watch->consume("status.txt")); // back: its file may be there already
    EXPECT_TRUE(watch->following());
    EXPECT_EQ(watch->problem(), "");
}

TEST(FolderWatch, AFolderThatNeverExistedIsRefusedNamingIt)
{
    auto watch = FolderWatch::open("/nonexistent-overlayd-folder", IN_CLOSE_WRITE);
    ASSERT_FALSE(watch.ok());
    EXPECT_NE(watch.error().message.find("/nonexistent-overlayd-folder"), std::string::npos);
}
