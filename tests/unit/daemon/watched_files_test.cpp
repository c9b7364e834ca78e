// SPDX-License-Identifier: Apache-2.0
// WatchedFiles on real folders: a file input's health says "waiting" (an error, logged once, with its time) while its
// folder is gone and "following" once it is back; a reload that keeps an input keeps its error count.
#include "control/watched_files.h"

#include <filesystem>
#include <poll.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

using State = InputHealth::State;

struct WatchedFilesTest : ::testing::Test {
    // One folder per test and process: CTest runs the tests of this file in parallel.
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        (std::string("overlayd-") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
         std::to_string(::getpid())) /
        "run";
    std::string file = (dir / "status.txt").string();
    std::vector<std::string> logged;
    std::vector<size_t> changed;
    Logger logger{[this](std::string_view line) { logged.emplace_back(line); }, true};
    WatchedFiles files{logger, "text", [this](size_t input) {
                           changed.push_back(input);
                       }};

    void SetUp() override { std::filesystem::create_directories(dir); }
    void TearDown() override { std::filesystem::remove_all(dir.parent_path()); }
    void watch(const std::string &name)
    {
        std::vector<TextFileWatch> watches;
        auto opened = TextFileWatch::open(file, 64);
        ASSERT_TRUE(opened.ok()) << opened.error().message;
        watches.push_back(std::move(*opened));
        files.replace(std::move(watches), {name});
    }
    // What the event loop does when the watch's fd becomes readable.
    void nextEvent()
    {
        pollfd p{files[0].fd(), POLLIN, 0};
        ASSERT_EQ(::poll(&p, 1, 1000), 1);
        files.onEvent(0);
    }
};

TEST_F(WatchedFilesTest, WaitingWhileTheFolderIsGoneFollowingOnceItIsBack)
{
    watch("status");
    const InputHealth &health = files.health()[0];
    EXPECT_EQ(health.kind, "text");
    EXPECT_EQ(health.name, "status");
    EXPECT_EQ(health.source, file);
    EXPECT_EQ(health.state, State::Following);
    EXPECT_EQ(health.errors, 0u);

    const auto before = InputHealth::WallClock::now();
    std::filesystem::remove_all(dir);
    nextEvent();
    EXPECT_EQ(files.health()[0].state, State::Waiting);
    EXPECT_EQ(files.health()[0].errors, 1u);
    EXPECT_NE(files.health()[0].lastError.find("the folder " + dir.string() + " is gone"), std::string::npos)
        << files.health()[0].lastError;
    EXPECT_GE(files.health()[0].lastErrorAt, before);
    EXPECT_EQ(changed, std::vector<size_t>{0}); // the file is gone with its folder: read it again
    ASSERT_FALSE(logged.empty());
    EXPECT_NE(logged.back().find("input.text 'status': the folder " + dir.string()), std::string::npos)
        << logged.back();

    const auto waitingSince = files.health()[0].since;
    std::filesystem::create_directories(dir);
    nextEvent();
    EXPECT_EQ(files.health()[0].state, State::Following);
    EXPECT_GT(files.health()[0].since, waitingSince);
    EXPECT_EQ(files.health()[0].errors, 1u); // the last error stays, with its time
    EXPECT_NE(logged.back().find("input.text 'status': following " + file + " again"), std::string::npos)
        << logged.back();
}

TEST_F(WatchedFilesTest, AReloadKeepsTheErrorCountOfAnInputItKeeps)
{
    watch("status");
    files.fail(0, "refused");
    watch("status");
    EXPECT_EQ(files.health()[0].errors, 1u);
    EXPECT_EQ(files.health()[0].lastError, "refused");
    watch("other slot");
    EXPECT_EQ(files.health()[0].errors, 0u);
    EXPECT_EQ(files.health()[0].lastError, "");
}

} // namespace
} // namespace overlayd
