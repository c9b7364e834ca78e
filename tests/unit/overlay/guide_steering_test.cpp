// SPDX-License-Identifier: Apache-2.0
// A live steering angle (setGuideSteering) moves the guide lines' wheel tracks onto the Ackermann circles for that
// angle, computed here from the formula the docs give (each rear wheel turns about (0, R), R = wheelbase /
// tan(angle)) and projected with GLM, not with the renderer's own path code; an unknown angle leaves only the
// distance marks, straight behind the car.
#include <cmath>
#include <vector>

#include <glm/ext/matrix_projection.hpp>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "scene_fixture.h"

namespace overlayd {
namespace {

constexpr unsigned kWidth = 640, kHeight = 480;
constexpr double kWheelbase = 2.7, kTrack = 1.6, kLength = 2.0;

OverlayScene guideScene()
{
    GuideLinesShape guide{kWheelbase, kTrack, 0.0, kLength, {1.0}, {}};
    return {{}, {test::annotation("guide", guide, kWhite, 3.0, "guides")}, std::nullopt};
}

// Where the rear wheel on `side` (+1 left, -1 right) is once the axle centre has backed up by s metres.
glm::dvec3 wheelAfter(double steeringDeg, int side, double s)
{
    const glm::dvec3 start(0.0, side * kTrack / 2, 0.0);
    if (steeringDeg == 0.0)
        return start - glm::dvec3(s, 0.0, 0.0);
    const double radius = kWheelbase / std::tan(steeringDeg * M_PI / 180.0);
    const double turn = -s / radius; // the body turns about (0, R)
    const glm::dvec2 fromCentre(start.x, start.y - radius);
    return {fromCentre.x * std::cos(turn) - fromCentre.y * std::sin(turn),
            radius + fromCentre.x * std::sin(turn) + fromCentre.y * std::cos(turn), 0.0};
}

// The pixel (top-left origin) GLM projects a world point to.
cv::Point pixelOf(const Camera &camera, const glm::dvec3 &point)
{
    const glm::dvec3 p =
        glm::projectNO(point, camera.view(), camera.projection().matrix(), glm::dvec4(0, 0, kWidth, kHeight));
    return {int(std::floor(p.x)), int(std::floor(kHeight - p.y))};
}

bool paintedNear(const cv::Mat &alpha, cv::Point at, int radius = 2)
{
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const cv::Point p = at + cv::Point(dx, dy);
            if (p.x >= 0 && p.y >= 0 && p.x < alpha.cols && p.y < alpha.rows && alpha.at<uint8_t>(p) > 0)
                return true;
        }
    return false;
}

struct TrackPaint {
    int inView = 0, painted = 0;
};
// Of the track points every 0.1 m that land inside the frame, how many have paint within 2 px.
TrackPaint paintedTrackPoints(const cv::Mat &alpha, const Camera &camera, double steeringDeg)
{
    TrackPaint out;
    for (int side : {1, -1})
        for (double s = 0.0; s <= kLength + 1e-9; s += 0.1) {
            const cv::Point p = pixelOf(camera, wheelAfter(steeringDeg, side, s));
            if (p.x < 0 || p.y < 0 || p.x >= int(kWidth) || p.y >= int(kHeight))
                continue;
            ++out.inView;
            out.painted += paintedNear(alpha, p) ? 1 : 0;
        }
    return out;
}

// Sets the angle and blends twice: a change right after another is drawn into the frame only; the frame after it
// (a steady wheel) renders the cached layers, whose pixels the tests read.
void steerAndSettle(SceneRenderer &renderer, std::optional<double> angle)
{
    test::TestFrame frame = test::makeFrame("RGB24", kWidth, kHeight, 0);
    ASSERT_TRUE(renderer.setGuideSteering("guide", angle));
    for (int i = 0; i < 2; ++i)
        ASSERT_TRUE(renderer.blend(frame.view(), FrameMetadata{}, 30.0));
    ASSERT_FALSE(renderer.drewDirectly());
}

TEST(GuideSteering, WheelTracksFollowTheAckermannCirclesAtEachAngle)
{
    const Camera camera = test::groundCamera(kWidth, kHeight);
    auto renderer = test::makeRenderer(guideScene(), camera, test::streamFormat("RGB24", kWidth, kHeight));
    for (double angle : {-30.0, -12.5, 0.0, 8.0, 25.0}) {
        steerAndSettle(*renderer, angle);
        const cv::Mat alpha = test::layerAlpha(*renderer->layerPixels("guides"));
        const TrackPaint track = paintedTrackPoints(alpha, camera, angle);
        EXPECT_GE(track.inView, 30) << "angle " << angle;
        EXPECT_EQ(track.painted, track.inView) << "angle " << angle;
        // The far end of the left track for a clearly different angle is not painted: the curve really moved.
        const double other = angle > 0 ? angle - 20.0 : angle + 20.0;
        EXPECT_FALSE(paintedNear(alpha, pixelOf(camera, wheelAfter(other, 1, kLength)), 1))
            << "angle " << angle << " also shows " << other;
    }
}

TEST(GuideSteering, UnknownAngleLeavesOnlyStraightMarks)
{
    const Camera camera = test::groundCamera(kWidth, kHeight);
    auto renderer = test::makeRenderer(guideScene(), camera, test::streamFormat("RGB24", kWidth, kHeight));
    steerAndSettle(*renderer, 20.0);
    steerAndSettle(*renderer, std::nullopt);
    const cv::Mat alpha = test::layerAlpha(*renderer->layerPixels("guides"));
    EXPECT_LE(paintedTrackPoints(alpha, camera, 0.0).painted, 2) << "only where the mark crosses the tracks";
    EXPECT_LE(paintedTrackPoints(alpha, camera, 20.0).painted, 2);
    // The 1 m mark, straight across behind the axle.
    const glm::dvec3 left = wheelAfter(0.0, 1, 1.0), right = wheelAfter(0.0, -1, 1.0);
    for (double t = 0.1; t < 1.0; t += 0.2)
        EXPECT_TRUE(paintedNear(alpha, pixelOf(camera, left + t * (right - left)))) << t;
    EXPECT_FALSE(renderer->setGuideSteering("no such guide", 1.0));
    EXPECT_FALSE(renderer->setGuideSteering("guide", 95.0));
}

TEST(GuideSteering, AChangeEveryFrameIsDrawnStraightIntoTheFrame)
{
    const Camera camera = test::groundCamera(kWidth, kHeight);
    auto renderer = test::makeRenderer(guideScene(), camera, test::streamFormat("RGB24", kWidth, kHeight));
    test::TestFrame frame = test::makeFrame("RGB24", kWidth, kHeight, 0);
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(renderer->setGuideSteering("guide", 5.0 + i));
        ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    }
    EXPECT_TRUE(renderer->drewDirectly());
    ASSERT_TRUE(renderer->setGuideSteering("guide", 7.0)); // the same angle: a steady wheel changes nothing
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    EXPECT_FALSE(renderer->drewDirectly());
}

} // namespace
} // namespace overlayd
