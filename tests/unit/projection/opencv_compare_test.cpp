// SPDX-License-Identifier: Apache-2.0
// opencv_compare_test: Camera pixels against cv::projectPoints / cv::fisheye::projectPoints on random cameras.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

using test::CvCamera;

constexpr double kPixelTolerance = 1e-6;
constexpr int kCameras = 200;
constexpr int kPointsPerCamera = 200;

class OpenCvCompare : public ::testing::TestWithParam<DistortionModel>
{};

// Both the single-point and the batch API must reproduce OpenCV to 1e-6 px for every random camera and point.
TEST_P(OpenCvCompare, PixelsEqualOpenCv)
{
    const DistortionModel model = GetParam();
    std::mt19937_64 rng(0x0c0ffee + static_cast<int>(model));
    double worst = 0.0;
    for (int cam = 0; cam < kCameras; ++cam) {
        const CvCamera c = test::randomCvCamera(rng, model);
        const DepthRange depth = cam % 2 ? DepthRange::ZeroToOne : DepthRange::MinusOneToOne;
        const Camera camera = test::makeCamera(c, depth);
        const double radius = test::testFieldRadius(camera);
        std::vector<glm::dvec3> world;
        for (int i = 0; i < kPointsPerCamera; ++i)
            world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 0.05, 500.0)));
        const std::vector<glm::dvec2> expected = test::cvProject(c, world);
        std::vector<ProjectedPoint> batch(world.size());
        camera.projectPoints(world, batch);
        for (std::size_t i = 0; i < world.size(); ++i) {
            const ProjectedPoint single = camera.project(world[i]);
            ASSERT_NE(single.status, PointStatus::Clipped) << "camera " << cam << " point " << i;
            ASSERT_NE(batch[i].status, PointStatus::Clipped) << "camera " << cam << " point " << i;
            const double error = glm::length(single.pixel - expected[i]);
            worst = std::max({worst, error, glm::length(batch[i].pixel - expected[i])});
            ASSERT_LE(error, kPixelTolerance)
                << test::modelName(model) << " camera " << cam << " point " << i << ": ours (" << single.pixel.x << ", "
                << single.pixel.y << "), OpenCV (" << expected[i].x << ", " << expected[i].y << ")";
            ASSERT_LE(glm::length(batch[i].pixel - expected[i]), kPixelTolerance)
                << test::modelName(model) << " batch, camera " << cam << " point " << i;
            EXPECT_EQ(batch[i].status, single.status);
            EXPECT_EQ(batch[i].depth, single.depth);
        }
    }
    RecordProperty("worst_error_px", std::to_string(worst));
}

// Visible exactly when OpenCV's pixel lies in the image rectangle [-0.5, W - 0.5] x [-0.5, H - 0.5] (pixel
// centres at integers), Outside otherwise; never Clipped for a point in front within the lens field.
TEST_P(OpenCvCompare, StatusFollowsImageRectangle)
{
    const DistortionModel model = GetParam();
    std::mt19937_64 rng(0x5ca1e + static_cast<int>(model));
    int visible = 0, outside = 0;
    for (int cam = 0; cam < 100; ++cam) {
        const CvCamera c = test::randomCvCamera(rng, model);
        const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne);
        // Out to about 56 degrees off-axis: enough points land on both sides of the image edge.
        const double radius = std::min(test::testFieldRadius(camera), 1.5);
        std::vector<glm::dvec3> world;
        for (int i = 0; i < 200; ++i)
            world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 0.1, 100.0)));
        const std::vector<glm::dvec2> expected = test::cvProject(c, world);
        for (std::size_t i = 0; i < world.size(); ++i) {
            const glm::dvec2 e = expected[i];
            const double margin = std::min({e.x + 0.5, c.width - 0.5 - e.x, e.y + 0.5, c.height - 0.5 - e.y});
            if (std::abs(margin) < 1e-5)
                continue; // on the border itself: either answer is within rounding
            const PointStatus want = margin > 0.0 ? PointStatus::Visible : PointStatus::Outside;
            EXPECT_EQ(camera.project(world[i]).status, want) << "camera " << cam << " point " << i;
            (want == PointStatus::Visible ? visible : outside)++;
        }
    }
    // The sampling must exercise both answers, or the test proves nothing.
    EXPECT_GT(visible, 1000);
    EXPECT_GT(outside, 1000);
}

INSTANTIATE_TEST_SUITE_P(Models, OpenCvCompare,
                         ::testing::Values(DistortionModel::None, DistortionModel::RadialTangential,
                                           DistortionModel::Rational, DistortionModel::Fisheye),
                         [](const auto &param) { return std::string(test::modelName(param.param)); });

// Exact corners: the image's outermost pixel centres are Visible, half a pixel beyond the edge is still Visible
// (the edge of the pixel), and just past that is Outside.
TEST(OpenCvCompareStatus, ImageEdgesFollowPixelCentreConvention)
{
    CvCamera c;
    c.rvec = {0, 0, 0};
    c.tvec = {0, 0, 0};
    c.fx = 500;
    c.fy = 500;
    c.cx = 319.5;
    c.cy = 239.5;
    c.width = 640;
    c.height = 480;
    const Camera camera = test::makeCamera(c, DepthRange::MinusOneToOne);
    // Optical point whose OpenCV pixel is (u, v): x = (u - cx) / fx at depth 1.
    auto at = [&](double u, double v) {
        return glm::dvec3((u - c.cx) / c.fx, (v - c.cy) / c.fy, 1.0);
    };
    struct Case {
        double u, v;
        PointStatus status;
    };
    const Case cases[] = {
        {0, 0, PointStatus::Visible},        {639, 479, PointStatus::Visible},
        {-0.4999, 10, PointStatus::Visible}, {639.4999, 10, PointStatus::Visible},
        {-0.5001, 10, PointStatus::Outside}, {639.5001, 10, PointStatus::Outside},
        {10, -0.5001, PointStatus::Outside}, {10, 479.5001, PointStatus::Outside},
    };
    for (const Case &k : cases) {
        const glm::dvec3 p = at(k.u, k.v);
        const ProjectedPoint projected = camera.project(p);
        const glm::dvec2 reference = test::cvProject(c, p);
        EXPECT_NEAR(projected.pixel.x, reference.x, kPixelTolerance);
        EXPECT_NEAR(projected.pixel.y, reference.y, kPixelTolerance);
        EXPECT_EQ(projected.status, k.status) << "pixel (" << k.u << ", " << k.v << ")";
    }
}

} // namespace
} // namespace overlayd
