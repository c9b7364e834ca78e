// SPDX-License-Identifier: Apache-2.0
// [[sink]] outputs are exclusive: two sinks on one file, however the path is spelled, or two on stdout, are refused
// at the second one's path with its line; different files and null sinks are fine.
#include <string>

#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

std::string sinks(const std::string &first, const std::string &second)
{
    return "[source]\nkind = \"synthetic\"\n"
           "[[sink]]\nkind = \"y4m\"\npath = \"" +
           first +
           "\"\n"
           "[[sink]]\nkind = \"raw\"\npath = \"" +
           second + "\"\n";
}

TEST(SinkOutputs, TwoSinksOnOneFileAreRefusedAtTheSecond)
{
    const auto problems = loadInvalid(sinks("out/a.y4m", "./out/../out/a.y4m"));
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "sink[1].path");
    EXPECT_EQ(problems[0].line, 8u);
    EXPECT_NE(problems[0].message.find("written by sink[0].path already"), std::string::npos) << problems[0].message;
}

TEST(SinkOutputs, TwoSinksOnStdoutAreRefused)
{
    const auto problems = loadInvalid(sinks("-", "-"));
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "sink[1].path");
    EXPECT_NE(problems[0].message.find("stdout is written by sink[0].path"), std::string::npos) << problems[0].message;
}

TEST(SinkOutputs, DifferentFilesAndNullSinksAreFine)
{
    EXPECT_EQ(loadValid(sinks("a.y4m", "a.raw")).sinks.size(), 2u);
    EXPECT_EQ(loadValid("[[sink]]\nkind = \"null\"\n[[sink]]\nkind = \"null\"\n").sinks.size(), 2u);
}

} // namespace
} // namespace overlayd::test
