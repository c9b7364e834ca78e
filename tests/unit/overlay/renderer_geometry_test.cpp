// SPDX-License-Identifier: Apache-2.0
// Geometry of the rendered overlay: viewport origins, clipping at the camera, and lens curvature against OpenCV.
#include <cmath>
#include <vector>

#include <glm/ext/matrix_projection.hpp>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "overlay/shapes/shape_builder.h"
#include "scene_fixture.h"

namespace overlayd {
namespace {

using test::annotation;

// A camera at the world origin in the internal frame (looking down -Z, Y up), 320x240, fx = fy = 256.
Camera originCamera(Origin origin = Origin::TopLeft, const Distortion &distortion = Distortion{}, int width = 320,
                    int height = 240)
{
    const PinholeIntrinsics k{256.0, 256.0, (width - 1) / 2.0, (height - 1) / 2.0, 0.0, width, height};
    const auto projection = Projection::pinhole(k, 0.1, 100.0, DepthRange::MinusOneToOne);
    const auto viewport = Viewport::create(ViewportSpec{width, height, std::nullopt, origin});
    return *Camera::create(Pose{}, *projection, distortion, *viewport);
}

cv::Mat render(const OverlayScene &scene, const Camera &camera, const std::string &layer = "default")
{
    auto renderer = test::makeRenderer(scene, camera,
                                       test::streamFormat("RGB24", unsigned(camera.viewport().frameWidth()),
                                                          unsigned(camera.viewport().frameHeight())));
    return test::layerAlpha(*renderer->layerPixels(layer)).clone();
}

OverlayScene worldOnly()
{
    OverlayScene scene = test::demoScene(false);
    std::erase_if(scene.annotations, [](const Annotation &a) { return std::holds_alternative<RectShape>(a.shape); });
    for (Annotation &a : scene.annotations)
        a.style.layer = "default";
    return scene;
}

// World annotations land on the same memory rows under both origins (the origin only changes how a user counts
// rows); screen items are given in the origin's convention, so they come out mirrored.
TEST(ViewportOrigin, WorldIdenticalScreenItemsMirrored)
{
    const OverlayScene world = worldOnly();
    const cv::Mat topLeft = render(world, test::groundCamera(320, 240, Origin::TopLeft));
    const cv::Mat bottomLeft = render(world, test::groundCamera(320, 240, Origin::BottomLeft));
    EXPECT_GT(cv::countNonZero(topLeft), 3000);
    // Up to one code: OpenCV blends each anti-aliased edge into the mask with integer rounding, so where two
    // segments overlap the result depends on their order, which the origins reverse for screen-sized markers.
    cv::Mat worldDiff;
    cv::absdiff(topLeft, bottomLeft, worldDiff);
    double worldWorst = 0;
    cv::minMaxLoc(worldDiff, nullptr, &worldWorst);
    EXPECT_LE(worldWorst, 1.0);

    OverlayScene screen;
    screen.annotations.push_back(annotation("cross", CrosshairShape{glm::dvec2(40.3, 30.7), 30.0}, kWhite, 2.5));
    screen.annotations.push_back(annotation("frame", RectShape{{100.0, 50.0}, {60.0, 30.0}, false}, kRed, 3.0));
    screen.annotations.push_back(annotation("fill", RectShape{{200.0, 20.0}, {17.0, 9.0}, true}, kGreen));
    const cv::Mat screenTop = render(screen, originCamera(Origin::TopLeft));
    cv::Mat screenBottom = render(screen, originCamera(Origin::BottomLeft));
    cv::flip(screenBottom, screenBottom, 0);
    // OpenCV's anti-aliasing is not symmetric under a vertical flip (edge pixels differ by up to ~50 codes), so the
    // mirror is checked on what it must keep: where the ink is (its weighted centre row) and how much there is.
    const cv::Moments top = cv::moments(screenTop), bottom = cv::moments(screenBottom);
    EXPECT_NEAR(top.m01 / top.m00, bottom.m01 / bottom.m00, 0.1);
    EXPECT_NEAR(top.m10 / top.m00, bottom.m10 / bottom.m00, 0.1);
    EXPECT_NEAR(top.m00, bottom.m00, 0.01 * top.m00);
    cv::Mat diff;
    cv::absdiff(screenTop, screenBottom, diff);
    EXPECT_LT(cv::sum(diff)[0], 0.05 * cv::sum(screenTop)[0]);
    EXPECT_GT(cv::countNonZero(screenTop), 500);

    // Text stays upright; its box is what mirrors: the corner nearest the origin sits at the given position.
    OverlayScene text;
    text.annotations.push_back(annotation("t", ScreenTextShape{"Hello", {10.0, 20.0}, 16.0, kBlue}, kWhite));
    cv::Mat textTop = render(text, originCamera(Origin::TopLeft)),
            textBottom = render(text, originCamera(Origin::BottomLeft));
    const cv::Rect boxTop = cv::boundingRect(textTop), boxBottom = cv::boundingRect(textBottom);
    EXPECT_EQ(boxTop.y, 20);
    EXPECT_EQ(boxBottom.y + boxBottom.height - 1, 239 - 20);
    EXPECT_EQ(boxTop.size(), boxBottom.size());
    EXPECT_EQ(boxTop.x, boxBottom.x);
}

// GLM's projectZO (and cv::projectPoints) put a point behind the camera onto the mirrored pixel in front; nothing
// behind the camera may produce a pixel here.
TEST(Clipping, NothingBehindTheCameraIsDrawn)
{
    const Camera camera = originCamera();
    const std::vector<glm::dvec3> behind{{-0.5, -0.4, 3.0}, {0.5, -0.4, 3.0}, {0.5, 0.4, 3.0}, {-0.5, 0.4, 3.0}};
    OverlayScene scene;
    scene.annotations.push_back(annotation("loop", PolylineShape{behind, true}, kWhite, 3.0));
    scene.annotations.push_back(annotation("marks", MarkersShape{behind, MarkerKind::Square, 12.0}, kWhite, 2.0));
    scene.annotations.push_back(annotation("label", LabelShape{{0.0, 0.0, 3.0}, "behind", {0.0, 0.0}, 20.0}, kWhite));
    scene.annotations.push_back(annotation("box", BoxShape{{0.0, 0.0, 4.0}, {1.0, 1.0, 1.0}}, kWhite, 3.0));
    EXPECT_EQ(cv::countNonZero(render(scene, camera)), 0);

    // The naive path would have drawn: GLM puts the loop's corners inside the image.
    const glm::dvec4 viewportRect(0, 0, 320, 240);
    const glm::dvec3 mirrored = glm::projectZO(behind[0], camera.view(), camera.projection().matrix(), viewportRect);
    EXPECT_GT(mirrored.x, 0.0);
    EXPECT_LT(mirrored.x, 320.0);
    EXPECT_GT(mirrored.y, 0.0);
    EXPECT_LT(mirrored.y, 240.0);
}

// A segment from in front of the camera to behind it is drawn exactly up to the near plane (z = -0.1).
TEST(Clipping, SegmentCrossingTheNearPlaneEndsThere)
{
    const glm::dvec3 front(0.0, -1.0, -5.0), back(0.02, 0.0, 0.05);
    OverlayScene scene;
    scene.annotations.push_back(annotation("seg", PolylineShape{{front, back}, false}, kWhite, 2.0));
    const cv::Mat alpha = render(scene, originCamera());

    // Independent reference: the crossing point and the pinhole formula (optical y = -internal y).
    const double t = (-0.1 - front.z) / (back.z - front.z);
    const glm::dvec3 crossing = front + t * (back - front);
    const cv::Point2d end(159.5 + 256.0 * crossing.x / 0.1, 119.5 - 256.0 * crossing.y / 0.1);
    const cv::Point2d start(159.5 + 256.0 * front.x / 5.0, 119.5 - 256.0 * front.y / 5.0);
    const cv::Point2d direction = (end - start) / cv::norm(end - start);
    double reach = -1e9;
    for (int y = 0; y < alpha.rows; ++y) {
        for (int x = 0; x < alpha.cols; ++x) {
            if (alpha.at<uint8_t>(y, x) > 64)
                reach = std::max(reach, (cv::Point2d(x, y) - start).dot(direction));
        }
    }
    EXPECT_NEAR(reach, cv::norm(end - start), 1.5) << "the line must reach the near plane's pixel and stop there";
}

struct CurveReference {
    std::vector<cv::Point2d> pixels; // cv::projectPoints of points along the 3D line
};

// A long straight line through a strongly distorting lens, compared with OpenCV's projection of its points.
TEST(LensCurvature, DistortedLineFollowsProjectPoints)
{
    const Distortion barrel{DistortionModel::RadialTangential, {-0.25, 0.08, 0.001, -0.0015, 0.0}};
    const int width = 640, height = 480;
    const Camera camera = originCamera(Origin::TopLeft, barrel, width, height);
    const glm::dvec3 a(-2.2, 1.1, -3.0), b(2.2, 1.3, -3.0);
    OverlayScene scene;
    scene.annotations.push_back(annotation("line", PolylineShape{{a, b}, false}, kWhite, 2.0));

    // OpenCV reference in the optical frame (y and z flipped), identity extrinsics.
    std::vector<cv::Point3d> optical;
    constexpr int kSamples = 2000;
    for (int i = 0; i <= kSamples; ++i) {
        const glm::dvec3 p = a + (b - a) * (double(i) / kSamples);
        optical.emplace_back(p.x, -p.y, -p.z);
    }
    const cv::Matx33d K(256, 0, (width - 1) / 2.0, 0, 256, (height - 1) / 2.0, 0, 0, 1);
    std::vector<cv::Point2d> reference;
    cv::projectPoints(optical, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                      std::vector<double>{-0.25, 0.08, 0.001, -0.0015, 0.0}, reference);
    const double sag = std::abs(reference[kSamples / 2].y - 0.5 * (reference.front().y + reference.back().y));
    ASSERT_GT(sag, 10.0) << "the lens must bend the line visibly for this test to mean anything";

    // The projected primitive: every polyline vertex lies on OpenCV's curve within 0.5 px.
    DrawList list;
    buildPrimitives(scene.annotations[0], glm::dmat4(1.0), camera, list);
    ASSERT_EQ(list.strokes.size(), 1u);
    for (const glm::dvec2 &p : list.strokes[0].lines.points) {
        double nearest = 1e9;
        for (const cv::Point2d &r : reference)
            nearest = std::min(nearest, std::hypot(r.x - p.x, r.y - p.y));
        EXPECT_LT(nearest, 0.5) << p.x << "," << p.y;
    }
    // The rasterized line: per column, the coverage-weighted centre row is on the curve within 0.5 px.
    const cv::Mat alpha = render(scene, camera);
    int checked = 0;
    for (size_t i = 1; i < reference.size(); ++i) {
        const cv::Point2d &p = reference[i - 1], &q = reference[i];
        const int x = int(std::ceil(p.x));
        if (x >= q.x || x < 5 || x >= width - 5)
            continue;
        const double yRef = p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x);
        double sum = 0, weighted = 0;
        for (int y = int(yRef) - 6; y <= int(yRef) + 6; ++y) {
            sum += alpha.at<uint8_t>(y, x);
            weighted += y * double(alpha.at<uint8_t>(y, x));
        }
        ASSERT_GT(sum, 0.0) << "column " << x;
        EXPECT_NEAR(weighted / sum, yRef, 0.5) << "column " << x;
        ++checked;
    }
    EXPECT_GT(checked, 300);
}

} // namespace
} // namespace overlayd
