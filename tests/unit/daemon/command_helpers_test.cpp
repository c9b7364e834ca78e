// SPDX-License-Identifier: Apache-2.0
// The `project --json` format (hand-written expected text) and render's choice of sink from the output path.
#include "base/json_text.h"
#include "tools/commands.h"

#include <iomanip>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace overlayd {
namespace {

TEST(ProjectionsJson, MatchesThePinnedFormat)
{
    const std::vector<glm::dvec3> world{{0, 0, 0}, {1.5, -2, 0.25}, {0, 0, -5}};
    std::vector<ProjectedPoint> points(3);
    points[0] = {{639.5, 359.5}, 0.5, PointStatus::Visible};
    points[1] = {{-20.25, 100}, 0.75, PointStatus::Outside};
    points[2] = {{0, 0}, 0, PointStatus::Clipped};
    const std::vector<PointReport> reports{{2.5, nullptr}, {4, "outside-viewport"}, {-5, "behind-camera"}};
    EXPECT_EQ(projectionsJson(world, points, reports),
              "[{\"world\":[0,0,0],\"pixel\":[639.5,359.5],\"depth\":0.5,\"distance\":2.5,\"visible\":true,"
              "\"reason\":null},\n"
              " {\"world\":[1.5,-2,0.25],\"pixel\":[-20.25,100],\"depth\":0.75,\"distance\":4,\"visible\":false,"
              "\"reason\":\"outside-viewport\"},\n"
              " {\"world\":[0,0,-5],\"pixel\":null,\"depth\":null,\"distance\":-5,\"visible\":false,"
              "\"reason\":\"behind-camera\"}]\n");
}

TEST(ProjectionsJson, NumbersRoundTripExactly)
{
    const double awkward = 0.1 + 0.2; // 0.30000000000000004: printing with %g would lose it
    std::vector<ProjectedPoint> points{{{awkward, 1.0 / 3.0}, awkward, PointStatus::Visible}};
    const std::string json = projectionsJson({{awkward, 0, 0}}, points, {{1.0, nullptr}});
    EXPECT_NE(json.find("\"pixel\":[0.30000000000000004,0.3333333333333333]"), std::string::npos) << json;
}

TEST(ProjectionsText, SaysWhatHappenedToEachPoint)
{
    std::vector<ProjectedPoint> points(2);
    points[0] = {{10, 20}, 0.5, PointStatus::Visible};
    points[1] = {{0, 0}, 0, PointStatus::Clipped};
    EXPECT_EQ(projectionsText({{1, 2, 3}, {0, 0, -1}}, points, {{3.0, nullptr}, {-1.0, "behind-camera"}}),
              "(1, 2, 3) -> pixel (10.000, 20.000), depth 0.500000, 3.000 m in front, visible\n"
              "(0, 0, -1) -> no pixel: behind-camera (1.000 m behind the camera)\n");
}

// No fixed-size buffer: a number of 251 digits is printed whole, and the line still ends where it should.
TEST(ProjectionsText, PrintsAHugeNumberWhole)
{
    std::vector<ProjectedPoint> points(1);
    points[0] = {{10, 20}, 0.5, PointStatus::Visible};
    std::ostringstream reference;
    reference << std::fixed << std::setprecision(3) << 1e250;
    const std::string text = projectionsText({{1, 2, 3}}, points, {{1e250, nullptr}});
    EXPECT_NE(text.find(", " + reference.str() + " m in front, visible\n"), std::string::npos) << text;
}

// A plane 1e30 m away along the ray: its distance is printed with all of its 31 digits, not cut at 31 characters.
TEST(UnprojectText, PrintsAFarHitWhole)
{
    const auto camera = CameraSpec{}.build(640, 480);
    ASSERT_TRUE(camera) << camera.error().message;
    const auto ray = camera->unproject({320, 240});
    ASSERT_TRUE(ray);
    const std::string text = unprojectText(*camera, Plane{ray->direction, -1e30}, {{320, 240}});
    const size_t away = text.rfind(" m away\n");
    ASSERT_NE(away, std::string::npos) << text;
    const size_t start = text.rfind(' ', away - 1) + 1;
    const std::string distance = text.substr(start, away - start);
    EXPECT_EQ(distance.find('.'), 31u) << text; // 31 digits, a point and 6 decimals
    EXPECT_NEAR(std::stod(distance) / 1e30, 1.0, 1e-9) << text;
}

// A card name or file name that is not UTF-8 (a driver's bytes) still prints as JSON: nlohmann's strict parser is the
// independent reader, and valid multi-byte characters and escapes come back unchanged.
TEST(JsonString, IsJsonWhateverTheBytes)
{
    const std::string valid = "caf\xC3\xA9 \"cam\"\\\t";
    // Eight bytes that are no UTF-8: a stray FF, an overlong C0 AF, a surrogate ED A0 80, a sequence cut short E2 82.
    const std::string invalid = "\xFF\xC0\xAF\xED\xA0\x80\xE2\x82";
    const nlohmann::json parsed = nlohmann::json::parse(jsonString(valid + invalid));
    std::string expected = valid;
    for (int i = 0; i < 8; ++i)
        expected += "\xEF\xBF\xBD"; // U+FFFD in UTF-8
    EXPECT_EQ(parsed.get<std::string>(), expected);
}

TEST(SinkForOutput, ExtensionPicksTheSink)
{
    EXPECT_EQ(sinkForOutput("out/a.y4m")->kind, SinkKind::Y4m);
    EXPECT_EQ(sinkForOutput("a.yuv")->kind, SinkKind::Raw);
    EXPECT_EQ(sinkForOutput("a.raw")->kind, SinkKind::Raw);
    const auto images = sinkForOutput("frames/%04d.png");
    ASSERT_TRUE(images.ok());
    EXPECT_EQ(images->kind, SinkKind::Snapshot);
    EXPECT_EQ(images->every, 1u);
    EXPECT_EQ(images->path, "frames/%04d.png");
    const auto unknown = sinkForOutput("out/a.mp4");
    ASSERT_FALSE(unknown.ok());
    EXPECT_NE(unknown.error().message.find("a.mp4"), std::string::npos);
}

} // namespace
} // namespace overlayd
