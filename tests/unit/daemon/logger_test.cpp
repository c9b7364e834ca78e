// SPDX-License-Identifier: Apache-2.0
// Logger: journald priority prefixes, readable timestamps otherwise, level filtering and the repeat limit.
#include "base/logger.h"

#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

struct Capture {
    std::vector<std::string> lines;
    std::chrono::steady_clock::time_point now{std::chrono::seconds(1000)};

    Logger logger(bool journal)
    {
        return Logger([this](std::string_view line) { lines.emplace_back(line); }, journal, [this] { return now; });
    }
};

TEST(Logger, JournalLinesCarrySyslogPriorities)
{
    Capture capture;
    Logger logger = capture.logger(true);
    logger.setLevel(LogLevel::Debug);
    logger.debug("d");
    logger.info("i");
    logger.notice("n");
    logger.warning("w");
    logger.error("e");
    // sd-daemon(3): SD_DEBUG "<7>", SD_INFO "<6>", SD_NOTICE "<5>", SD_WARNING "<4>", SD_ERR "<3>".
    const std::vector<std::string> expected{"<7>d\n", "<6>i\n", "<5>n\n", "<4>w\n", "<3>e\n"};
    EXPECT_EQ(capture.lines, expected);
}

TEST(Logger, TerminalLinesCarryTimestampAndLevel)
{
    Capture capture;
    Logger logger = capture.logger(false);
    logger.warning("camera lost");
    ASSERT_EQ(capture.lines.size(), 1u);
    const std::regex pattern(R"(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3} warning: camera lost\n)");
    EXPECT_TRUE(std::regex_match(capture.lines[0], pattern)) << capture.lines[0];
}

TEST(Logger, LevelFiltersLowerPriorities)
{
    Capture capture;
    Logger logger = capture.logger(true);
    logger.setLevel(LogLevel::Warning);
    logger.info("hidden");
    logger.notice("hidden too");
    logger.error("shown");
    EXPECT_EQ(capture.lines, std::vector<std::string>{"<3>shown\n"});
}

TEST(Logger, IdenticalRepeatsAreCountedNotPrinted)
{
    Capture capture;
    Logger logger = capture.logger(true);
    for (int i = 0; i < 5; ++i)
        logger.error("no frame");
    logger.error("something else");
    const std::vector<std::string> expected{"<3>no frame\n", "<3>last message repeated 4 times\n",
                                            "<3>something else\n"};
    EXPECT_EQ(capture.lines, expected);
}

TEST(Logger, RepeatsPrintAgainAfterTheWindow)
{
    Capture capture;
    Logger logger = capture.logger(true);
    logger.error("no frame");
    logger.error("no frame");
    capture.now += Logger::kRepeatWindow + std::chrono::seconds(1);
    logger.error("no frame");
    logger.error("no frame");
    logger.flush();
    const std::vector<std::string> expected{"<3>no frame\n", "<3>last message repeated 1 times\n", "<3>no frame\n",
                                            "<3>last message repeated 1 times\n"};
    EXPECT_EQ(capture.lines, expected);
}

TEST(Logger, SameTextAtAnotherLevelIsNotARepeat)
{
    Capture capture;
    Logger logger = capture.logger(true);
    logger.warning("x");
    logger.error("x");
    EXPECT_EQ(capture.lines, (std::vector<std::string>{"<4>x\n", "<3>x\n"}));
}

TEST(Logger, ParsesLevelNames)
{
    LogLevel level = LogLevel::Info;
    EXPECT_TRUE(parseLogLevel("warning", level));
    EXPECT_EQ(level, LogLevel::Warning);
    EXPECT_FALSE(parseLogLevel("loud", level));
    EXPECT_EQ(level, LogLevel::Warning);
}

} // namespace
} // namespace overlayd
