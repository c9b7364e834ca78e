// SPDX-License-Identifier: Apache-2.0
// The command line: subcommands, the default `run`, options that fall through, and usage errors.
#include "tools/cli.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

struct CliTest : ::testing::Test {
    // CLI11 checks that --config files exist. CTest runs each test in its own process, in parallel: one file each.
    std::string config = ::testing::TempDir() + "cli_test_" + std::to_string(getpid()) + ".toml";
    void SetUp() override { std::ofstream(config) << "\n"; }
    void TearDown() override { std::remove(config.c_str()); }

    static CommandLine parse(std::vector<std::string> args)
    {
        args.insert(args.begin(), "overlayd");
        std::vector<const char *> argv;
        for (const std::string &arg : args)
            argv.push_back(arg.c_str());
        return parseCommandLine(int(argv.size()), argv.data());
    }
};

TEST_F(CliTest, RunIsTheDefaultSubcommand)
{
    const CommandLine line = parse({"--config", config});
    EXPECT_EQ(line.command, Command::Run);
    EXPECT_EQ(line.configPath, config);
    EXPECT_EQ(line.frames, 0u);
}

TEST_F(CliTest, RunTakesAFrameLimitAndALogLevel)
{
    const CommandLine line = parse({"run", "--config", config, "--frames", "30", "--log-level", "debug"});
    EXPECT_EQ(line.command, Command::Run);
    EXPECT_EQ(line.frames, 30u);
    ASSERT_TRUE(line.logLevel.has_value());
    EXPECT_EQ(*line.logLevel, LogLevel::Debug);
}

TEST_F(CliTest, CheckConfigTakesTheFileAsAnArgument)
{
    const CommandLine line = parse({"check-config", "missing.toml"});
    EXPECT_EQ(line.command, Command::CheckConfig);
    EXPECT_EQ(line.configPath, "missing.toml");
}

TEST_F(CliTest, ProjectTakesCoordinatesIncludingNegativesAfterDashDash)
{
    const CommandLine line = parse({"project", "--config", config, "--json", "--", "1", "-2.5", "0", "-1", "0", "3"});
    EXPECT_EQ(line.command, Command::Project);
    EXPECT_TRUE(line.json);
    EXPECT_EQ(line.coordinates, (std::vector<double>{1, -2.5, 0, -1, 0, 3}));
}

TEST_F(CliTest, RenderNeedsFramesAndOutput)
{
    const CommandLine line = parse({"render", "--config", config, "--frames", "5", "--output", "out/x.y4m"});
    EXPECT_EQ(line.command, Command::Render);
    EXPECT_EQ(line.frames, 5u);
    EXPECT_EQ(line.output, "out/x.y4m");
    const CommandLine missing = parse({"render", "--config", config, "--output", "out/x.y4m"});
    EXPECT_EQ(missing.command, Command::Exit);
    EXPECT_NE(missing.exitStatus, 0);
}

TEST_F(CliTest, UsageErrorsExitNonZero)
{
    EXPECT_NE(parse({"run", "--config", "/nonexistent/overlayd.toml"}).exitStatus, 0);
    EXPECT_NE(parse({"run", "--config", config, "--log-level", "loud"}).exitStatus, 0);
    EXPECT_NE(parse({"run", "--config", config, "--bogus"}).exitStatus, 0);
}

TEST_F(CliTest, VersionExitsZero)
{
    const CommandLine line = parse({"--version"});
    EXPECT_EQ(line.command, Command::Exit);
    EXPECT_EQ(line.exitStatus, 0);
}

} // namespace
} // namespace overlayd
