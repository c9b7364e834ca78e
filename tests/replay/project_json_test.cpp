// `overlayd project --json` against points computed by hand. The camera (tests/data/replay/project_*.toml) sits at
// the origin looking along +X with Z up, vertical fov 90 degrees on 320x240: f = 120 / tan(45 deg) = 120 px on
// both axes, principal point (159.5, 119.5). A point at distance d ahead, y to the left and z up lands on
// u = 159.5 - 120 y / d, v = 119.5 - 120 z / d (top-left origin; bottom-left: 239 - v). OpenGL depth with near 1,
// far 100: 101/99 - 200 / (99 d).
#include <regex>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::replay {
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

} // namespace
} // namespace overlayd::replay
