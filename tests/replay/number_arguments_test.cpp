// SPDX-License-Identifier: Apache-2.0
// Numbers given on the command line and in points files, through the real binary: each one finite and in the
// config file's range (kAnyMagnitude), or refused naming the argument (exit 2) or the file and line; a plane
// written large or small is the same plane.
#include <string>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

std::string example()
{
    return std::string(OVERLAYD_SOURCE_DIR) + "/config/examples/distorted_pinhole.toml";
}

void expectRefused(const RunResult &run, const std::string &named)
{
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 2) << run.all();
    EXPECT_NE(run.err.find(named), std::string::npos) << run.all();
    EXPECT_NE(run.err.find("out of range"), std::string::npos) << run.all();
    EXPECT_EQ(run.out, "") << run.all();
}

TEST(NumberArguments, ProjectRefusesNanAndHugeCoordinates)
{
    const std::string dir = scratchDir("numbers-project");
    const std::string project = "project --config '" + example() + "' -- ";
    expectRefused(runOverlayd(project + "nan 0 0", dir), "project: X of point 1");
    expectRefused(runOverlayd(project + "0 0 0 1 inf 2", dir), "project: Y of point 2");
    expectRefused(runOverlayd(project + "0 0 1e308", dir), "project: Z of point 1");
    EXPECT_EQ(runOverlayd(project + "0 5 0", dir).exitStatus, 0);
}

TEST(NumberArguments, UnprojectRefusesNanAndHugePixels)
{
    const std::string dir = scratchDir("numbers-unproject");
    const std::string unproject = "unproject --config '" + example() + "' -- ";
    expectRefused(runOverlayd(unproject + "nan nan", dir), "unproject: U of pixel 1");
    expectRefused(runOverlayd(unproject + "640 500 1e308 5", dir), "unproject: U of pixel 2");
    expectRefused(runOverlayd(unproject + "640 -inf", dir), "unproject: V of pixel 1");
}

TEST(NumberArguments, APlaneWrittenLargeOrSmallIsTheSamePlane)
{
    const std::string dir = scratchDir("numbers-plane");
    const std::string unproject = "unproject --config '" + example() + "' --plane ";
    const RunResult unit = runOverlayd(unproject + "\"0 -1 0 6\" -- 640 5", dir);
    ASSERT_EQ(unit.exitStatus, 0) << unit.all();
    EXPECT_NE(unit.out.find("meets the plane at ("), std::string::npos) << unit.out;
    for (const std::string scaled : {"\"0 -1e-300 0 6e-300\"", "\"0 -1e5 0 6e5\"", "\"0 -4.9e-324 0 2.5e-323\""}) {
        const RunResult run = runOverlayd(unproject + scaled + " -- 640 5", dir);
        EXPECT_EQ(run.exitStatus, 0) << scaled << ": " << run.all();
        if (scaled.find("e-324") == std::string::npos) { // 2.5e-323 / 4.9e-324 is 5, not 6
            EXPECT_EQ(run.out, unit.out) << scaled;
        }
    }
    const RunResult behind = runOverlayd(unproject + "\"0 0 1 -3\" -- 640 5", dir);
    const RunResult behindLarge = runOverlayd(unproject + "\"0 0 1e5 -3e5\" -- 640 5", dir);
    ASSERT_EQ(behind.exitStatus, 0) << behind.all();
    EXPECT_EQ(behindLarge.out, behind.out) << behindLarge.all();
    expectRefused(runOverlayd(unproject + "\"0 0 1e308 -3e308\" -- 640 5", dir), "unproject: nz of --plane 1");
    expectRefused(runOverlayd(unproject + "\"0 0 1 1e30\" -- 640 5", dir), "unproject: d of --plane 1");
    const RunResult zero = runOverlayd(unproject + "\"0 0 0 1\" -- 640 5", dir);
    EXPECT_EQ(zero.exitStatus, 2) << zero.all();
    EXPECT_NE(zero.err.find("must not be zero"), std::string::npos) << zero.all();
}

TEST(NumberArguments, PointsFilesRefuseHugeNumbersAtTheirLine)
{
    const std::string dir = scratchDir("numbers-points");
    writeFile(dir + "/far.csv", "0 1 0 640 500\n1 1 0 700 500\n1e300 2 0 600 400\n0 3 0 640 300\n1 4 1 700 200\n");
    RunResult run = runOverlayd("solve-pose --config '" + example() + "' --points far.csv", dir);
    EXPECT_FALSE(run.crashed) << run.all();
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("far.csv:3: '1e300' out of range"), std::string::npos) << run.all();
    EXPECT_EQ(run.err.find("OpenCV"), std::string::npos) << run.all();

    writeFile(dir + "/far.json", "[{\"world\": [0, 1, 0], \"pixel\": [640, 500]},\n"
                                 " {\"world\": [0, 1, -1e300], \"pixel\": [640, 500]}]\n");
    run = runOverlayd("solve-pose --config '" + example() + "' --points far.json", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("far.json:2: element 1: \"world\": out of range"), std::string::npos) << run.all();

    // project reads solve-pose's points format: the same words.
    writeFile(dir + "/far.xyz", "0 1 0\n0 1e300 0\n");
    run = runOverlayd("project --config '" + example() + "' --points far.xyz", dir);
    EXPECT_EQ(run.exitStatus, 1) << run.all();
    EXPECT_NE(run.err.find("far.xyz:2: '1e300' out of range"), std::string::npos) << run.all();
}

} // namespace
} // namespace overlayd::test
