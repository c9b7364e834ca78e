// SPDX-License-Identifier: Apache-2.0
// `overlayd project --json` against points computed by hand. The camera (tests/data/replay/project_*.toml) sits at
// the origin looking along +X with Z up, vertical fov 90 degrees on 320x240: f = 120 / tan(45 deg) = 120 px on
// both axes, principal point (159.5, 119.5). A point at distance d ahead, y to the left and z up lands on
// u = 159.5 - 120 y / d, v = 119.5 - 120 z / d (top-left origin; bottom-left: 239 - v). OpenGL depth with near 1,
// far 100: 101/99 - 200 / (99 d).
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

struct Expected {
    bool clipped;
    double u, v, depth;
    bool visible;
    double distance; // metres ahead along the optical axis (+X here)
    const char *reason;
};

void expectProjections(const std::string &config, bool bottomLeft)
{
    const RunResult run = runOverlayd("project --config '" + dataPath(config) +
                                          "' --json -- 10 0 0  10 -2 1  5 1 -1  -5 0 0  10 20 0  200 0 0  0.5 0 0",
                                      scratchDir(config));
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    const double d10 = 101.0 / 99.0 - 200.0 / (99.0 * 10.0), d5 = 101.0 / 99.0 - 200.0 / (99.0 * 5.0);
    const std::vector<Expected> expected{
        {false, 159.5, 119.5, d10, true, 10, "null"},                  // straight ahead: the principal point
        {false, 183.5, 107.5, d10, true, 10, "null"},                  // 2 m right, 1 m up at 10 m
        {false, 135.5, 143.5, d5, true, 5, "null"},                    // 1 m left, 1 m down at 5 m
        {true, 0, 0, 0, false, -5, "\"behind-camera\""},               // clipped, no pixel
        {false, -80.5, 119.5, d10, false, 10, "\"outside-viewport\""}, // left of the image: a pixel, not visible
        {true, 0, 0, 0, false, 200, "\"beyond-far\""},
        {true, 0, 0, 0, false, 0.5, "\"before-near\""},
    };
    const std::regex object(R"(\{"world":\[([^\]]*)\],"pixel":(null|\[([^,]+),([^\]]+)\]),"depth":([^,]+),)"
                            R"("distance":([^,]+),"visible":(true|false),"reason":([^}]+)\})");
    auto it = std::sregex_iterator(run.out.begin(), run.out.end(), object);
    size_t i = 0;
    for (; it != std::sregex_iterator() && i < expected.size(); ++it, ++i) {
        const std::smatch &m = *it;
        const Expected &e = expected[i];
        SCOPED_TRACE("point " + std::to_string(i) + ": " + m.str());
        EXPECT_EQ(m[7] == "true", e.visible);
        EXPECT_NEAR(std::stod(m[6]), e.distance, 1e-12);
        EXPECT_EQ(m[8], e.reason);
        if (e.clipped) {
            EXPECT_EQ(m[2], "null");
            EXPECT_EQ(m[5], "null");
            continue;
        }
        ASSERT_NE(m[2], "null");
        EXPECT_NEAR(std::stod(m[3]), e.u, 1e-9);
        EXPECT_NEAR(std::stod(m[4]), bottomLeft ? 239.0 - e.v : e.v, 1e-9);
        EXPECT_NEAR(std::stod(m[5]), e.depth, 1e-12);
    }
    EXPECT_EQ(i, expected.size()) << run.out;
    EXPECT_EQ(run.out.front(), '[');
}

TEST(ProjectJson, TopLeftOriginMatchesHandComputedPixels)
{
    expectProjections("project_top_left.toml", false);
}

TEST(ProjectJson, BottomLeftOriginFlipsRows)
{
    expectProjections("project_bottom_left.toml", true);
}

TEST(ProjectJson, OddNumberOfCoordinatesIsAnError)
{
    const RunResult run =
        runOverlayd("project --config '" + dataPath("project_top_left.toml") + "' 1 2", scratchDir("project-odd"));
    EXPECT_NE(run.exitStatus, 0);
    EXPECT_FALSE(run.crashed);
    EXPECT_NE(run.err.find("X Y Z"), std::string::npos) << run.err;
}

// --points reads the same "x y z" lines as [[input.path]], from a file or stdin, and gives what the coordinates give.
TEST(ProjectJson, PointsFromAFileOrStdinAreTheCoordinates)
{
    const std::string dir = scratchDir("project-points");
    {
        std::ofstream file(dir + "/points.txt");
        file << "# ahead, then 2 m right and 1 m up\n10 0 0\n10, -2, 1\n";
    }
    const std::string config = "project --config '" + dataPath("project_top_left.toml") + "' --json ";
    const RunResult fromArgs = runOverlayd(config + "-- 10 0 0 10 -2 1", dir);
    const RunResult fromFile = runOverlayd(config + "--points points.txt", dir);
    const RunResult fromStdin = runOverlayd(config + "--points - < points.txt", dir);
    ASSERT_EQ(fromArgs.exitStatus, 0) << fromArgs.all();
    EXPECT_NE(fromArgs.out.find("\"pixel\":[183.5,107.5]"), std::string::npos) << fromArgs.out;
    EXPECT_EQ(fromFile.out, fromArgs.out) << fromFile.all();
    EXPECT_EQ(fromStdin.out, fromArgs.out) << fromStdin.all();

    {
        std::ofstream file(dir + "/bad.txt");
        file << "10 0 0\n10 0\n";
    }
    const RunResult bad = runOverlayd(config + "--points bad.txt", dir);
    EXPECT_EQ(bad.exitStatus, 1);
    EXPECT_NE(bad.err.find("bad.txt:2: expected x y z or x y z u v, got 2 numbers"), std::string::npos) << bad.err;
    const RunResult both = runOverlayd(config + "--points points.txt -- 1 2 3", dir);
    EXPECT_EQ(both.exitStatus, 1);
    EXPECT_NE(both.err.find("not both"), std::string::npos) << both.err;
}

// --size: the 90 degree camera on a 640x480 stream has f = 240 px and its principal point at (319.5, 239.5).
TEST(ProjectJson, SizeProjectsForAnotherStream)
{
    const RunResult run =
        runOverlayd("project --config '" + dataPath("project_top_left.toml") + "' --json --size 640x480 -- 10 -2 1",
                    scratchDir("project-size"));
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    EXPECT_NE(run.out.find("\"pixel\":[367.5,215.5]"), std::string::npos) << run.out; // 319.5 + 48, 239.5 - 24
    const RunResult bad =
        runOverlayd("project --config '" + dataPath("project_top_left.toml") + "' --size 640by480 -- 10 0 0",
                    scratchDir("project-size"));
    EXPECT_NE(bad.exitStatus, 0);
    EXPECT_NE(bad.err.find("WIDTHxHEIGHT"), std::string::npos) << bad.err;
}

// The two reasons the hand-computed camera cannot show: a scissor that cuts the view, and a lens whose valid field
// ends before the image does (distorted_pinhole.toml's plumb_bob turns back 60 degrees off axis).
TEST(ProjectJson, OutsideTheScissorAndOutsideTheImageCircleSaySo)
{
    const std::string dir = scratchDir("project-reasons");
    {
        std::ofstream file(dir + "/scissor.toml");
        const std::vector<uint8_t> base = readFile(dataPath("project_top_left.toml"));
        file << std::string(base.begin(), base.end()) << "scissor = [0, 0, 160, 240]\n"; // the file ends in [viewport]
    }
    const RunResult scissor = runOverlayd("project --config scissor.toml --json -- 10 0.5 0 10 -2 0", dir);
    ASSERT_EQ(scissor.exitStatus, 0) << scissor.all();
    // 0.5 m left lands at u = 153.5, inside the scissor's left half; 2 m right at 183.5, outside it.
    EXPECT_NE(scissor.out.find("\"pixel\":[153.5,119.5],\"depth\""), std::string::npos) << scissor.out;
    EXPECT_NE(scissor.out.find("\"visible\":false,\"reason\":\"outside-scissor\""), std::string::npos) << scissor.out;
    const RunResult circle = runOverlayd("project --config '" + std::string(OVERLAYD_SOURCE_DIR) +
                                             "/config/examples/distorted_pinhole.toml" + "' --json -- 20 1 0",
                                         dir);
    ASSERT_EQ(circle.exitStatus, 0) << circle.all();
    EXPECT_NE(circle.out.find("\"pixel\":null"), std::string::npos) << circle.out;
    EXPECT_NE(circle.out.find("\"reason\":\"outside-image-circle\""), std::string::npos) << circle.out;
}

} // namespace
} // namespace overlayd::test
