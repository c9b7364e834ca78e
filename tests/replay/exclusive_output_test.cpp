// Exclusive outputs (issue 19, class 5): `check-config` and `run` refuse two sinks on one file or on stdout at the
// second's file:line:key.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::replay {
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

} // namespace
} // namespace overlayd::replay
