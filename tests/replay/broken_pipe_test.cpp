// SPDX-License-Identifier: Apache-2.0
// `overlayd run ... | ffplay -`: when the reader of the Y4M stream on stdout goes away, the daemon is not killed.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

TEST(BrokenPipe, ReaderGoingAwayDoesNotKillTheDaemon)
{
    const std::string dir = scratchDir("broken-pipe");
    writeFile(dir + "/stdout.toml", "[daemon]\nlog_level = \"warning\"\nstats_interval = 0.0\n"
                                    "[source]\nkind = \"synthetic\"\nformat = \"YUYV\"\nwidth = 320\nheight = 240\n"
                                    "fps = 200.0\n[source.synthetic]\npattern = \"colour-bars\"\n"
                                    "[[sink]]\nkind = \"y4m\"\npath = \"-\"\n");
    // head reads one frame's worth and exits; the daemon then writes into a pipe nobody reads.
    const std::string command = "cd '" + dir + "' && { " + binaryCommand() +
                                " run --config stdout.toml --frames 100 2> overlayd.stderr; echo $? > status; } | "
                                "head -c 200000 > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const auto status = readFile(dir + "/status");
    const int exitStatus = std::atoi(std::string(status.begin(), status.end()).c_str());
    const auto err = readFile(dir + "/overlayd.stderr");
    EXPECT_LT(exitStatus, 128) << "killed by a signal (141 = SIGPIPE); stderr:\n"
                               << std::string(err.begin(), err.end());
}

} // namespace
} // namespace overlayd::test
