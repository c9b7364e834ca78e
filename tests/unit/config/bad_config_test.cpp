// SPDX-License-Identifier: Apache-2.0
// Broken configs under tests/data/config/bad/: each gives the expected problem at the expected line, and a file
// with many problems gets all of them in one pass.
#include <string>

#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

std::string badFile(const std::string &name)
{
    return sourceDir() + "/tests/data/config/bad/" + name;
}

std::vector<ConfigProblem> loadBad(const std::string &name)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(badFile(name), problems);
    EXPECT_FALSE(config.ok()) << name;
    if (!config) {
        EXPECT_EQ(config.error().code, ErrorCode::ConfigError);
    }
    return problems;
}

std::string dump(const std::vector<ConfigProblem> &problems)
{
    std::string all;
    for (const ConfigProblem &p : problems)
        all += p.format() + "\n";
    return all;
}

// True when some problem sits on `line` with `key` (empty: any) and a message containing `text`.
bool has(const std::vector<ConfigProblem> &problems, unsigned line, const std::string &key, const std::string &text)
{
    for (const ConfigProblem &p : problems)
        if (p.line == line && (key.empty() || p.key == key) && p.message.find(text) != std::string::npos)
            return true;
    return false;
}

#define EXPECT_PROBLEM(problems, line, key, text) EXPECT_TRUE(has(problems, line, key, text)) << dump(problems)

TEST(BadConfig, SyntaxError)
{
    const auto problems = loadBad("syntax_error.toml");
    ASSERT_EQ(problems.size(), 1u) << dump(problems);
    EXPECT_PROBLEM(problems, 4, "", "syntax error");
    EXPECT_GT(problems[0].column, 0u);
    EXPECT_EQ(problems[0].file, badFile("syntax_error.toml"));
}

TEST(BadConfig, WrongTypes)
{
    const auto problems = loadBad("wrong_type.toml");
    EXPECT_PROBLEM(problems, 3, "source.width", "expected an integer, got a string");
    EXPECT_PROBLEM(problems, 7, "annotation[0].style.colour", "expected a colour");
    EXPECT_EQ(problems.size(), 2u) << dump(problems);
}

TEST(BadConfig, OutOfRange)
{
    const auto problems = loadBad("out_of_range.toml");
    EXPECT_PROBLEM(problems, 3, "source.width", "out of range");
    EXPECT_PROBLEM(problems, 4, "source.fps", "must be in (0, 1000] (got 0)");
    EXPECT_PROBLEM(problems, 7, "camera.position[1]", "must be in [-1e+06, 1e+06] (got nan)");
    EXPECT_PROBLEM(problems, 13, "sink[0].buffers", "out of range");
    EXPECT_EQ(problems.size(), 4u) << dump(problems);
}

TEST(BadConfig, UnknownKeysSuggestTheNearestKey)
{
    const auto problems = loadBad("unknown_key.toml");
    EXPECT_PROBLEM(problems, 4, "source.widht", "did you mean 'width'?");
    EXPECT_PROBLEM(problems, 9, "camera.fvo", "did you mean 'fov'?");
    // The column is the key's own.
    for (const ConfigProblem &p : problems)
        EXPECT_EQ(p.column, 1u);
}

TEST(BadConfig, MissingCalibrationFile)
{
    const auto problems = loadBad("missing_calibration.toml");
    ASSERT_EQ(problems.size(), 1u) << dump(problems);
    EXPECT_PROBLEM(problems, 3, "camera.calibration", "does not exist");
    EXPECT_NE(problems[0].message.find("no-such-calibration.yaml"), std::string::npos);
}

TEST(BadConfig, MalformedCalibrationFile)
{
    const auto problems = loadBad("malformed_calibration.toml");
    ASSERT_EQ(problems.size(), 1u) << dump(problems);
    EXPECT_PROBLEM(problems, 3, "camera.calibration", "malformed_calibration.yaml");
}

TEST(BadConfig, ProjectionRefusalLandsOnTheUpKey)
{
    const auto problems = loadBad("degenerate_up.toml");
    ASSERT_EQ(problems.size(), 1u) << dump(problems);
    EXPECT_PROBLEM(problems, 5, "camera.up", "parallel");
}

TEST(BadConfig, EveryProblemInOnePass)
{
    const auto problems = loadBad("many_problems.toml");
    EXPECT_PROBLEM(problems, 3, "daemon.log_level", "unknown value 'verbose'");
    EXPECT_PROBLEM(problems, 7, "source.format", "did you mean 'YUYV'?");
    EXPECT_PROBLEM(problems, 9, "source.height", "out of range");
    EXPECT_PROBLEM(problems, 13, "camera.calibration", "does not exist");
    EXPECT_PROBLEM(problems, 19, "annotation[0].frame", "did you mean 'world'?");
    EXPECT_PROBLEM(problems, 20, "annotation[0].spacing", "expected a number");
    EXPECT_PROBLEM(problems, 23, "annotation[1].type", "unknown annotation type 'circel'");
    EXPECT_PROBLEM(problems, 28, "sink[0].queue_depht", "did you mean 'queue_depth'?");
    EXPECT_EQ(problems.size(), 8u) << dump(problems);
    // In file order, and formatted as file:line:column: key: message.
    for (size_t i = 1; i < problems.size(); ++i)
        EXPECT_LE(problems[i - 1].line, problems[i].line);
    EXPECT_EQ(problems.front().format(), badFile("many_problems.toml") +
                                             ":3:13: daemon.log_level: unknown value 'verbose' (expected debug | "
                                             "info | notice | warning | error)");
}

TEST(BadConfig, MissingFile)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(badFile("does-not-exist.toml"), problems);
    ASSERT_FALSE(config.ok());
    EXPECT_EQ(config.error().code, ErrorCode::ConfigError);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].message, "the config file does not exist");
}

} // namespace
} // namespace overlayd::test
