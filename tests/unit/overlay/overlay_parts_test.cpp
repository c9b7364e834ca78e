// SPDX-License-Identifier: Apache-2.0
// The renderer's parts against hand-computed values: tokens, dash patterns, Ackermann guide lines, stroke widths.
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "overlay/raster/dash.h"
#include "overlay/raster/rasterizer.h"
#include "overlay/shapes/guide_lines.h"
#include "overlay/shapes/text_tokens.h"
#include "scene_fixture.h"

namespace overlayd {
namespace {

TEST(TextTokens, ExpandsEveryToken)
{
    setenv("TZ", "UTC", 1);
    tzset();
    FrameMetadata metadata;
    metadata.sequence = 1234;
    // 2024-02-29 13:45:06.789 UTC
    metadata.wallClock = std::chrono::system_clock::time_point(std::chrono::milliseconds(1709214306789LL));
    std::string out;
    expandTokens("{{f}} #{frame} {fps}fps {time:%Y-%m-%d %H:%M:%S}.{ms}", metadata, 29.97, out);
    EXPECT_EQ(out, "{f} #1234 30.0fps 2024-02-29 13:45:06.789");
    expandTokens("plain", metadata, 0, out);
    EXPECT_EQ(out, "plain");
    EXPECT_TRUE(hasTokens("a {frame}"));
    EXPECT_FALSE(hasTokens("a {{frame}}"));
    EXPECT_TRUE(checkTokens("{time:%H}{ms}{{}}").ok());
    EXPECT_FALSE(checkTokens("{frames}").ok());
    EXPECT_FALSE(checkTokens("{frame").ok());
    EXPECT_FALSE(checkTokens("}").ok());
    EXPECT_TRUE(checkTokens("gear {slot:gear-1.a_b}").ok());
    EXPECT_FALSE(checkTokens("{slot:}").ok());
    EXPECT_FALSE(checkTokens("{slot:a b}").ok());
    const SlotTexts slots{{"gear", "R"}};
    expandTokens("gear {slot:gear}{slot:speed}", metadata, 0, out, &slots);
    EXPECT_EQ(out, "gear R");
    // A gain or frame rate of any size is printed whole (the largest float, the largest double).
    metadata.analogueGain = 3.0e38f;
    std::ostringstream gain, fps;
    gain << std::fixed << std::setprecision(2) << double(3.0e38f);
    fps << std::fixed << std::setprecision(1) << 1.7e308;
    expandTokens("{gain}|{fps}", metadata, 1.7e308, out);
    EXPECT_EQ(out, gain.str() + "|" + fps.str());
    std::vector<std::string> names;
    appendSlotNames("{slot:a} {frame} {{slot:b}} {slot:c} {slot:a}", names);
    EXPECT_EQ(names, (std::vector<std::string>{"a", "c"}));
}

TEST(Dash, PiecesFollowArcLength)
{
    Polylines line, out;
    line.start({0, 0});
    line.extend({30, 0});
    line.extend({30, 40}); // 70 px in all, turning a corner
    const double pattern[] = {10, 5};
    applyDash(line, pattern, out);
    // On-intervals start every 15 px: 0-10, 15-25, 30-40, 45-55, 60-70.
    ASSERT_EQ(out.size(), 5u);
    EXPECT_EQ(out[0].front(), glm::dvec2(0, 0));
    EXPECT_EQ(out[0].back(), glm::dvec2(10, 0));
    EXPECT_EQ(out[1].front(), glm::dvec2(15, 0));
    EXPECT_EQ(out[2].front(), glm::dvec2(30, 0));
    EXPECT_EQ(out[2].back(), glm::dvec2(30, 10));
    EXPECT_EQ(out[4].front(), glm::dvec2(30, 30));
    EXPECT_EQ(out[4].back(), glm::dvec2(30, 40));
    // The dash that turns the corner (25-40 is off then on: 30-40 starts exactly at the corner).
    EXPECT_EQ(out[1].back(), glm::dvec2(25, 0));
}

// A pattern finer than kMinDashPeriodPx (a 1e-9 px dash along 1000 px would be 10^12 steps) is drawn solid, and
// negative or nan entries (which would walk backwards or stall) count as 0: each returns, with a bounded output.
TEST(Dash, PatternsThatWouldNeverEndAreBounded)
{
    Polylines line;
    line.start({0, 0});
    line.extend({1000, 0});
    for (const std::vector<double> &pattern :
         std::vector<std::vector<double>>{{1e-9, 1e-9}, {0.3, 0.3}, {-5, 2}, {std::nan(""), 1}, {0, 0}}) {
        Polylines out;
        applyDash(line, pattern, out);
        EXPECT_LE(out.points.size(), 2100u) << pattern[0] << ", " << pattern[1];
    }
    Polylines solid;
    const double fine[] = {1e-9, 1e-9};
    applyDash(line, fine, solid);
    ASSERT_EQ(solid.size(), 1u);
    EXPECT_EQ(solid[0].front(), glm::dvec2(0, 0));
    EXPECT_EQ(solid[0].back(), glm::dvec2(1000, 0));
    // A negative "on" counts as 0: off 2 px, on 0 px, ... (a dot every 2 px, 500 of them along 1000 px).
    Polylines dots;
    const double negative[] = {-5, 2};
    applyDash(line, negative, dots);
    EXPECT_GE(dots.size(), 499u);
    EXPECT_LE(dots.size(), 502u);
}

// With steering, each rear wheel runs on a circle about the turning centre (0, R), R = wheelbase / tan(steering);
// the axle centre has covered arc length d at each mark.
TEST(GuideLines, AckermannCircles)
{
    GuideLinesShape shape;
    shape.wheelbase = 2.7;
    shape.trackWidth = 1.6;
    shape.steeringDeg = 30.0;
    shape.length = 4.0;
    shape.distanceMarks = {1.0, 3.0, 9.0}; // 9 m is past the guide's length: dropped
    const GuideGeometry g = guideGeometry(shape);
    const double radius = 2.7 / std::tan(30.0 * M_PI / 180.0); // 4.6765 m
    const glm::dvec3 centre(0.0, radius, 0.0);
    for (const glm::dvec3 &p : g.wheels[0])
        EXPECT_NEAR(glm::distance(p, centre), radius - 0.8, 1e-9);
    for (const glm::dvec3 &p : g.wheels[1])
        EXPECT_NEAR(glm::distance(p, centre), radius + 0.8, 1e-9);
    EXPECT_LT(g.wheels[0].back().x, -2.5); // backing up goes to -x
    EXPECT_GT(g.wheels[0].back().y, 0.8);  // and, steering left, swings to +y
    ASSERT_EQ(g.marks.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        const double d = i == 0 ? 1.0 : 3.0;
        const glm::dvec3 mid = 0.5 * (g.marks[i][0] + g.marks[i][1]);
        const double angle = d / radius;
        EXPECT_NEAR(mid.x, -radius * std::sin(angle), 1e-9);
        EXPECT_NEAR(mid.y, radius * (1 - std::cos(angle)), 1e-9);
        EXPECT_NEAR(glm::distance(g.marks[i][0], g.marks[i][1]), 1.6, 1e-9);
    }
    shape.steeringDeg = 0.0;
    const GuideGeometry straight = guideGeometry(shape);
    EXPECT_NEAR(straight.wheels[0].back().x, -4.0, 1e-12);
    EXPECT_NEAR(straight.wheels[0].back().y, 0.8, 1e-12);
    EXPECT_NEAR(straight.wheels[1].back().y, -0.8, 1e-12);
}

// Coverage summed across a stroke (per column, over the line's length) equals its width, through the Rasterizer
// into a layer: the analytic box-filter coverage integrates to the width exactly for widths >= 1, up to 8-bit
// rounding (measured worst: 0.02 px).
TEST(StrokeWidth, CoverageAcrossMatchesWidth)
{
    TextRenderer text;
    Rasterizer rasterizer(text);
    for (double width : {1.0, 1.5, 2.0, 3.0, 5.0, 8.5}) {
        for (double y : {20.0, 20.25, 20.5}) {
            for (double slope : {0.0, 0.3}) {
                OverlayLayer layer(200, 100);
                DrawList list;
                StrokeItem stroke{StrokeStyle{kWhite, width, {}, true}, {}};
                stroke.lines.start({10, y});
                stroke.lines.extend({190, y + 180 * slope});
                list.strokes.push_back(stroke);
                rasterizer.draw(list, layer, {0, 0}, {0, 0, 200, 100});
                const cv::Mat alpha = test::layerAlpha(layer);
                const double across = cv::sum(alpha.colRange(60, 140))[0] / 255.0 / 80.0 / std::sqrt(1 + slope * slope);
                EXPECT_NEAR(across, width, 0.1) << "width " << width << " at y " << y << " slope " << slope;
            }
        }
    }
}

} // namespace
} // namespace overlayd
