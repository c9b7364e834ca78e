// SPDX-License-Identifier: Apache-2.0
// The log level: the config's daemon.log_level applies to `render` too, and --log-level overrides it.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

// A golden scene's config with its log level replaced.
std::string configWithLogLevel(const std::string &dir, const std::string &level)
{
    std::ifstream in(dataPath("persp_yuyv_top_left.toml"));
    std::stringstream buffer;
    buffer << in.rdbuf();
    std::string text = buffer.str();
    const std::string key = "log_level = \"warning\"";
    const size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << "the scene config no longer sets log_level";
    if (at != std::string::npos)
        text.replace(at, key.size(), "log_level = \"" + level + "\"");
    const std::string path = dir + "/quiet.toml";
    writeFile(path, text);
    return path;
}

TEST(LogLevel, RenderHonoursTheConfigsLevel)
{
    const std::string dir = scratchDir("log-level-config");
    const std::string config = configWithLogLevel(dir, "error");
    const RunResult run = runOverlayd("render --config '" + config + "' --frames 2 --output out.y4m", dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_EQ(run.err.find("info:"), std::string::npos) << "info lines at log_level = error:\n" << run.err;
}

TEST(LogLevel, CommandLineOverridesTheConfig)
{
    const std::string dir = scratchDir("log-level-override");
    const std::string config = configWithLogLevel(dir, "error");
    const RunResult run =
        runOverlayd("--log-level info render --config '" + config + "' --frames 2 --output out.y4m", dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.err.find("info:"), std::string::npos) << "no info lines with --log-level info:\n" << run.err;
}

} // namespace
} // namespace overlayd::test
