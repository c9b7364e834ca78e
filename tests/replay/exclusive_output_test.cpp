// SPDX-License-Identifier: Apache-2.0
// Exclusive outputs (issue 19, class 5): `check-config` and `run` refuse two sinks on one file or on stdout at the
// second's file:line:key, and a second daemon on the first's output file is refused at start naming its pid.
#include <csignal>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "harness.h"
#include "process.h"

namespace overlayd::test {
namespace {

std::string config(const std::string &sinks)
{
    return "[daemon]\nstats_interval = 0.0\n"
           "[source]\nkind = \"synthetic\"\nformat = \"YUYV\"\nwidth = 160\nheight = 120\nfps = 30.0\n" +
           sinks;
}

TEST(ExclusiveOutputs, CheckConfigAndRunRefuseTwoSinksOnOneOutput)
{
    const std::string dir = scratchDir("two-sinks-one-output");
    writeFile(dir + "/file.toml", config("[[sink]]\nkind = \"y4m\"\npath = \"out.y4m\"\n"
                                         "[[sink]]\nkind = \"y4m\"\npath = \"./out.y4m\"\n"));
    writeFile(dir + "/stdout.toml", config("[[sink]]\nkind = \"y4m\"\npath = \"-\"\n"
                                           "[[sink]]\nkind = \"y4m\"\npath = \"-\"\n"));
    for (const char *name : {"file.toml", "stdout.toml"}) {
        const std::string where = std::string(name) + ":14:8: sink[1].path: ";
        for (const std::string command : {"check-config ", "run --frames 1 --config "}) {
            const RunResult result = runOverlayd(command + name, dir);
            EXPECT_EQ(result.exitStatus, 2) << command << name << "\n" << result.all();
            EXPECT_NE(result.all().find(where), std::string::npos) << command << name << "\n" << result.all();
            EXPECT_NE(result.all().find("written by sink[0].path already"), std::string::npos) << result.all();
        }
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.y4m")) << "run wrote before refusing";
}

TEST(ExclusiveOutputs, ASecondDaemonOnTheSameFileIsRefusedNamingTheFirst)
{
    const std::string dir = scratchDir("two-daemons-one-file");
    writeFile(dir + "/overlayd.toml", config("[[sink]]\nkind = \"y4m\"\npath = \"out.y4m\"\n"));
    const pid_t first = startDaemon(dir, "overlayd.toml");
    ASSERT_GT(first, 0);
    const auto size = [&] {
        std::error_code error;
        const auto bytes = std::filesystem::file_size(dir + "/out.y4m", error);
        return error ? 0 : bytes;
    };
    ASSERT_TRUE(waitFor([&] { return size() > 0; })) << fileText(dir + "/overlayd.stderr");

    const RunResult second = runOverlayd("run --frames 5 --config overlayd.toml", dir);
    EXPECT_FALSE(second.crashed) << second.all();
    EXPECT_EQ(second.exitStatus, 1) << second.all();
    // The holder's name as the kernel knows it: overlayd natively, qemu-aarch64 when the arm64 tier emulates it.
    std::string holder = fileText("/proc/" + std::to_string(first) + "/comm");
    holder = holder.substr(0, holder.find('\n'));
    EXPECT_NE(second.all().find("out.y4m: locked by process " + std::to_string(first) + " (" + holder + ")"),
              std::string::npos)
        << second.all();
    const auto sizeAfter = size();
    EXPECT_TRUE(waitFor([&] { return size() > sizeAfter; })) << "the first daemon's output stopped growing";

    kill(first, SIGTERM);
    const auto ending = waitForExit(first, std::chrono::seconds(5));
    ASSERT_TRUE(ending);
    EXPECT_EQ(ending->exitStatus, 0);
    // The file is still the first's own: one header, then whole frames (160x120 YUYV: 38400 bytes + "FRAME\n").
    const std::string y4m = fileText(dir + "/out.y4m");
    ASSERT_EQ(y4m.rfind("YUV4MPEG2", 0), 0u);
    EXPECT_EQ((y4m.size() - (y4m.find('\n') + 1)) % (38400 + 6), 0u);
}

} // namespace
} // namespace overlayd::test
