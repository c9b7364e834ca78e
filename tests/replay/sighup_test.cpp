// SPDX-License-Identifier: Apache-2.0
// SIGHUP with `overlayd run`: a bad config is refused with every problem at file:line and the old one keeps
// running; a good one switches sinks without a restart; SIGTERM then ends cleanly with complete files. Run with
// JOURNAL_STREAM set, so the log lines must carry syslog priority prefixes.
#include <csignal>
#include <filesystem>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "harness.h"
#include "process.h"

namespace overlayd::test {
namespace {

namespace fs = std::filesystem;

TEST(Sighup, BadConfigIsRefusedAndGoodConfigSwitchesSinks)
{
    const std::string dir = scratchDir("sighup");
    const std::string config = dir + "/overlayd.toml";
    fs::copy_file(dataPath("sighup_good.toml"), config);
    const pid_t pid = startDaemon(dir, "overlayd.toml");
    ASSERT_GT(pid, 0);
    const auto size = [&](const char *name) {
        std::error_code error;
        const auto bytes = fs::file_size(dir + "/" + name, error);
        return error ? 0 : bytes;
    };
    EXPECT_TRUE(waitFor([&] { return size("a.y4m") > 100000; })) << fileText(dir + "/overlayd.stderr");

    fs::copy_file(dataPath("sighup_bad.toml"), config, fs::copy_options::overwrite_existing);
    kill(pid, SIGHUP);
    EXPECT_TRUE(
        waitFor([&] { return fileText(dir + "/overlayd.stderr").find("reload refused") != std::string::npos; }));
    const std::string afterBad = fileText(dir + "/overlayd.stderr");
    EXPECT_NE(afterBad.find("<3>overlayd.toml:16:1: sink[0].knd: unknown key"), std::string::npos) << afterBad;
    const auto sizeAfterBad = size("a.y4m");
    EXPECT_TRUE(waitFor([&] { return size("a.y4m") > sizeAfterBad; })) << "the old config stopped running";
    EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), 0) << "the daemon exited";

    fs::copy_file(dataPath("sighup_switched.toml"), config, fs::copy_options::overwrite_existing);
    kill(pid, SIGHUP);
    EXPECT_TRUE(waitFor([&] { return size("b.y4m") > 100000; })) << fileText(dir + "/overlayd.stderr");
    kill(pid, SIGTERM);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);

    const std::string log = fileText(dir + "/overlayd.stderr");
    EXPECT_NE(log.find("<5>reloaded overlayd.toml (sinks re-opened)"), std::string::npos) << log;
    // Both files end on a whole frame: 160x120 YUYV is 38400 bytes, plus "FRAME\n", after the header line.
    for (const char *name : {"a.y4m", "b.y4m"}) {
        const std::string y4m = fileText(dir + "/" + name);
        const size_t header = y4m.find('\n') + 1;
        ASSERT_GT(header, 1u) << name;
        EXPECT_EQ((y4m.size() - header) % (38400 + 6), 0u) << name;
    }
}

} // namespace
} // namespace overlayd::test
