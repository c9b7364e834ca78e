// SPDX-License-Identifier: Apache-2.0
// unproject_test: unproject(project(p)) is a ray through p, for every projection form, lens, origin and window.
//
// Independent references: GLM (glm::lookAt) builds the poses' inverse, cv::undistortPoints and
// cv::fisheye::undistortPoints give the rays of distorted cameras.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <opencv2/calib3d.hpp>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

using test::CvCamera;

constexpr double kRelative = 1e-9;

// Distance from p to the half-line origin + s direction (s >= 0), relative to p's distance from the origin.
double relativeRayDistance(const Ray &ray, const glm::dvec3 &p)
{
    const glm::dvec3 v = p - ray.origin;
    const double along = glm::dot(v, ray.direction);
    const double distance = along >= 0.0 ? glm::length(glm::cross(v, ray.direction)) / glm::length(ray.direction)
                                         : glm::length(v); // behind the ray's start: the origin is the nearest
    return distance / std::max(glm::length(v), 1e-300);
}

struct ViewportCase {
    const char *name;
    Origin origin;
    bool window; // a window placed inside a larger frame
};

const ViewportCase kViewports[] = {
    {"TopLeft", Origin::TopLeft, false},
    {"BottomLeft", Origin::BottomLeft, false},
    {"TopLeftWindow", Origin::TopLeft, true},
    {"BottomLeftWindow", Origin::BottomLeft, true},
};

// A 640x480 window; with `window`, at (150, 70) inside a 1000x800 frame.
ViewportSpec viewportSpec(const ViewportCase &v, int width = 640, int height = 480)
{
    ViewportSpec spec{width, height};
    if (v.window) {
        spec.frameWidth = width + 360;
        spec.frameHeight = height + 320;
        spec.window = PixelRect{150, 70, width, height};
    }
    spec.origin = v.origin;
    return spec;
}

// Projects random points in front of the camera and checks each one's unprojected ray passes through it.
void checkRoundTrip(const Camera &camera, const glm::dmat4 &worldFromCamera, double zMin, double zMax,
                    double halfWidthAtZ1, double halfWidthConst, const std::string &what)
{
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int checked = 0;
    double worst = 0.0;
    for (int i = 0; i < 3000; ++i) {
        const double z = zMin + (zMax - zMin) * 0.5 * (u(rng) + 1.0);
        const double half = halfWidthAtZ1 * z + halfWidthConst;
        const glm::dvec3 cameraSpace(u(rng) * half, u(rng) * half * 0.75, -z);
        const glm::dvec3 p = glm::dvec3(worldFromCamera * glm::dvec4(cameraSpace, 1.0));
        const ProjectedPoint projected = camera.project(p);
        if (projected.status == PointStatus::Clipped)
            continue;
        auto ray = camera.unproject(projected.pixel);
        ASSERT_TRUE(ray.ok()) << what << ": " << ray.error().message;
        EXPECT_NEAR(glm::length(ray->direction), 1.0, 1e-12);
        const double error = relativeRayDistance(*ray, p);
        worst = std::max(worst, error);
        ASSERT_LE(error, kRelative) << what << ": point " << i << " (" << p.x << ", " << p.y << ", " << p.z
                                    << ") is off its own ray";
        ++checked;
    }
    EXPECT_GT(checked, 2000) << what;
}

class Unproject : public ::testing::TestWithParam<std::tuple<ViewportCase, DepthRange>>
{
protected:
    ViewportCase viewportCase() const { return std::get<0>(GetParam()); }
    DepthRange depth() const { return std::get<1>(GetParam()); }
    std::string label(const char *projection) const
    {
        return std::string(projection) + " " + viewportCase().name +
               (depth() == DepthRange::ZeroToOne ? " ZeroToOne" : " MinusOneToOne");
    }
};

const glm::dvec3 kEye(2.0, -1.0, 4.0), kTarget(0.5, 0.3, -3.0), kUp(0.1, 1.0, 0.2);

TEST_P(Unproject, Perspective)
{
    auto viewport = Viewport::create(viewportSpec(viewportCase()));
    ASSERT_TRUE(viewport.ok());
    auto projection = Projection::perspective(FovAxis::Vertical, 55.0, viewport->windowAspect(), 0.1, 500.0, depth());
    auto camera = Camera::create(*poseLookAt(kEye, kTarget, kUp), *projection, Distortion{}, *viewport);
    ASSERT_TRUE(camera.ok());
    checkRoundTrip(*camera, glm::inverse(glm::lookAt(kEye, kTarget, kUp)), 0.2, 400.0, 0.8, 0.0, label("perspective"));
    // Perspective rays start at the camera centre.
    auto ray = camera->unproject({320.0, 240.0});
    ASSERT_TRUE(ray.ok());
    EXPECT_LE(glm::length(ray->origin - kEye), 1e-12 * glm::length(kEye));
}

TEST_P(Unproject, OffAxisFrustumWithInfiniteFar)
{
    auto viewport = Viewport::create(viewportSpec(viewportCase()));
    auto projection = Projection::frustum({-0.07, 0.05, -0.03, 0.06, 0.1, kInfiniteFar}, depth());
    ASSERT_TRUE(projection.ok());
    auto camera = Camera::create(*poseLookAt(kEye, kTarget, kUp), *projection, Distortion{}, *viewport);
    ASSERT_TRUE(camera.ok());
    checkRoundTrip(*camera, glm::inverse(glm::lookAt(kEye, kTarget, kUp)), 0.2, 1e6, 0.7, 0.0,
                   label("infinite-far frustum"));
}

TEST_P(Unproject, Orthographic)
{
    auto viewport = Viewport::create(viewportSpec(viewportCase()));
    auto projection = Projection::orthographic({-4.0, 3.0, -2.5, 2.0, 0.5, 80.0}, depth());
    ASSERT_TRUE(projection.ok());
    auto camera = Camera::create(*poseLookAt(kEye, kTarget, kUp), *projection, Distortion{}, *viewport);
    ASSERT_TRUE(camera.ok());
    checkRoundTrip(*camera, glm::inverse(glm::lookAt(kEye, kTarget, kUp)), 0.6, 79.0, 0.0, 4.5, label("orthographic"));
    // Orthographic rays are all parallel to the viewing direction and start on the near plane.
    const glm::dvec3 forward = glm::normalize(kTarget - kEye);
    for (const glm::dvec2 pixel : {glm::dvec2(0, 0), glm::dvec2(500, 300)}) {
        auto ray = camera->unproject(pixel);
        ASSERT_TRUE(ray.ok());
        EXPECT_NEAR(glm::dot(ray->direction, forward), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(ray->origin - kEye, forward), 0.5, 1e-12);
    }
}

TEST_P(Unproject, PinholeWithEachLens)
{
    std::mt19937_64 rng(41);
    for (const DistortionModel model : {DistortionModel::None, DistortionModel::RadialTangential,
                                        DistortionModel::Rational, DistortionModel::Fisheye}) {
        for (int k = 0; k < 10; ++k) {
            CvCamera c = test::randomCvCamera(rng, model);
            c.width = 640;
            c.height = 480;
            c.fx = c.width * (model == DistortionModel::Fisheye ? 0.3 : 0.8);
            c.fy = c.fx * 1.02;
            c.cx = 330.2;
            c.cy = 235.7;
            const ViewportSpec spec = viewportSpec(viewportCase(), c.width, c.height);
            const Camera camera = test::makeCamera(c, depth(), 0.01, 1000.0, &spec);
            // World from optical, then optical from camera (OpenGL) space: flip y and z.
            cv::Matx33d r;
            cv::Rodrigues(c.rvec, r);
            glm::dmat4 worldFromCamera(1.0);
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row)
                    worldFromCamera[col][row] = r(col, row) * (col == 0 ? 1.0 : -1.0); // R^T, columns 1, 2 negated
            const cv::Vec3d centre = -(r.t() * c.tvec);
            worldFromCamera[3] = glm::dvec4(centre[0], centre[1], centre[2], 1.0);
            const double field = std::min(test::testFieldRadius(camera), 1.2);
            checkRoundTrip(camera, worldFromCamera, 0.05, 500.0, 0.7 * field, 0.0,
                           label("pinhole") + " " + test::modelName(model));
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Viewports, Unproject,
                         ::testing::Combine(::testing::ValuesIn(kViewports),
                                            ::testing::Values(DepthRange::MinusOneToOne, DepthRange::ZeroToOne)),
                         [](const auto &param) {
                             return std::string(std::get<0>(param.param).name) +
                                    (std::get<1>(param.param) == DepthRange::ZeroToOne ? "_ZeroToOne"
                                                                                       : "_MinusOneToOne");
                         });

// For distorted cameras, our ray's direction matches OpenCV's undistortion of the same pixel: normalized
// (x, y) from cv::undistortPoints (cv::fisheye::undistortPoints), direction R^T (x, y, 1) in the world.
TEST(UnprojectOpenCv, RaysMatchUndistortPoints)
{
    std::mt19937_64 rng(43);
    for (const DistortionModel model :
         {DistortionModel::RadialTangential, DistortionModel::Rational, DistortionModel::Fisheye}) {
        for (int k = 0; k < 20; ++k) {
            const CvCamera c = test::randomCvCamera(rng, model);
            const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne);
            cv::Matx33d r;
            cv::Rodrigues(c.rvec, r);
            // OpenCV's iterations converge more slowly than Newton's far out: stay within the inner field.
            const double field = std::min(test::testFieldRadius(camera), 0.7);
            std::vector<cv::Point2d> pixels;
            for (int i = 0; i < 100; ++i) {
                const glm::dvec2 px =
                    test::cvProject(c, test::worldFromOptical(c, test::randomOpticalPoint(rng, field, 1.0, 10.0)));
                pixels.emplace_back(px.x, px.y);
            }
            std::vector<cv::Point2d> normalized;
            const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 1000, 1e-15);
            if (model == DistortionModel::Fisheye) {
                const cv::Vec4d d(c.distortion.coeffs[0], c.distortion.coeffs[1], c.distortion.coeffs[2],
                                  c.distortion.coeffs[3]);
                cv::fisheye::undistortPoints(pixels, normalized, c.cameraMatrix(), d, cv::noArray(), cv::noArray(),
                                             criteria);
            } else {
                cv::undistortPoints(pixels, normalized, c.cameraMatrix(), c.distCoeffs(), cv::noArray(), cv::noArray(),
                                    criteria);
            }
            for (std::size_t i = 0; i < pixels.size(); ++i) {
                auto ray = camera.unproject({pixels[i].x, pixels[i].y});
                ASSERT_TRUE(ray.ok()) << ray.error().message;
                const cv::Vec3d w = r.t() * cv::Vec3d(normalized[i].x, normalized[i].y, 1.0);
                const glm::dvec3 want = glm::normalize(glm::dvec3(w[0], w[1], w[2]));
                EXPECT_LE(glm::length(ray->direction - want), 1e-8)
                    << test::modelName(model) << " camera " << k << " pixel (" << pixels[i].x << ", " << pixels[i].y
                    << ")";
            }
        }
    }
}

} // namespace
} // namespace overlayd
