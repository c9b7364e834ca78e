// SPDX-License-Identifier: Apache-2.0
// wide_fisheye_test: fisheye lenses of 185, 200 and 220 degrees, which see points behind the camera plane.
//
// The reference is OpenCV's fisheye model written out here on the angle from the axis (cv::fisheye cannot take
// z <= 0): theta = atan2(|(X, Y)|, Z), theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8),
// u = fx theta_d X / |(X, Y)| + cx, v = fy theta_d Y / |(X, Y)| + cy, with (X, Y, Z) = R(rvec) x + tvec by
// cv::Rodrigues; in front of the camera cv::fisheye::projectPoints checks the same pixels.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

using test::CvCamera;
using test::uniform;

constexpr double kDegree = M_PI / 180.0;

struct WideLens {
    double fovDeg;           // the field of view the image circle shows
    std::array<double, 4> k; // k1..k4
};

// theta_d as OpenCV writes it, and its derivative 1 + 3 k1 t^2 + 5 k2 t^4 + 7 k3 t^6 + 9 k4 t^8.
double thetaD(const std::array<double, 4> &k, double t)
{
    return t * (1 + k[0] * std::pow(t, 2) + k[1] * std::pow(t, 4) + k[2] * std::pow(t, 6) + k[3] * std::pow(t, 8));
}

double slope(const std::array<double, 4> &k, double t)
{
    return 1 + 3 * k[0] * t * t + 5 * k[1] * std::pow(t, 4) + 7 * k[2] * std::pow(t, 6) + 9 * k[3] * std::pow(t, 8);
}

// The first angle where the slope turns negative, by bisection on the derivative (not by the code's scan).
double modelLimit(const std::array<double, 4> &k)
{
    double lo = 0.0, hi = M_PI;
    if (slope(k, hi) > 0)
        return 179.99 * kDegree;
    for (int i = 0; i < 200; ++i)
        (slope(k, 0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    return lo;
}

// Equidistant (grows forever), and two lenses whose models turn at 148 degrees (1 - 0.15 t^2 = 0) and at 121
// degrees (1 - 0.05 t^4 = 0).
const WideLens kLenses[] = {
    {185.0, {0.0, 0.0, 0.0, 0.0}},
    {200.0, {-0.05, 0.0, 0.0, 0.0}},
    {220.0, {0.0, -0.01, 0.0, 0.0}},
};

// The lens as a config declares it: its field of view (max_field_deg), or a wider one given.
CvCamera wideCamera(const WideLens &lens, std::mt19937_64 &rng, double declaredFieldDeg = 0.0)
{
    CvCamera c;
    c.rvec = {uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3)};
    c.tvec = {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)};
    c.width = 1600;
    c.height = 1200;
    // The image circle of the field of view fills the image's height.
    c.fy = 0.5 * c.height / thetaD(lens.k, 0.5 * lens.fovDeg * kDegree);
    c.fx = c.fy * 1.01;
    c.cx = 801.3;
    c.cy = 598.7;
    c.distortion = {DistortionModel::Fisheye,
                    {lens.k[0], lens.k[1], lens.k[2], lens.k[3]},
                    declaredFieldDeg > 0.0 ? declaredFieldDeg : lens.fovDeg};
    return c;
}

glm::dvec3 opticalOf(const CvCamera &c, const glm::dvec3 &world)
{
    cv::Matx33d r;
    cv::Rodrigues(c.rvec, r);
    const cv::Vec3d o = r * cv::Vec3d(world.x, world.y, world.z) + c.tvec;
    return {o[0], o[1], o[2]};
}

glm::dvec2 referencePixel(const CvCamera &c, const glm::dvec3 &world)
{
    const glm::dvec3 o = opticalOf(c, world);
    const double r = std::hypot(o.x, o.y);
    const std::array<double, 4> k{c.distortion.coeffs[0], c.distortion.coeffs[1], c.distortion.coeffs[2],
                                  c.distortion.coeffs[3]};
    const double td = thetaD(k, std::atan2(r, o.z));
    return {c.fx * td * o.x / r + c.cx, c.fy * td * o.y / r + c.cy};
}

// A world point at `distance` from the camera, `angle` from the optical axis, azimuth phi.
glm::dvec3 pointAt(const CvCamera &c, double angle, double phi, double distance)
{
    const glm::dvec3 o(distance * std::sin(angle) * std::cos(phi), distance * std::sin(angle) * std::sin(phi),
                       distance * std::cos(angle));
    return test::worldFromOptical(c, o);
}

// Declared as wide as a field can be (just under a full turn), the model's own limit decides.
// Every batch loop gives the single-point path's statuses and bits.
void expectBatchIsSinglePoint(const Camera &camera, const std::vector<glm::dvec3> &world)
{
    for (BatchKernel kernel : {BatchKernel::Lanes2, BatchKernel::Lanes4Avx2, BatchKernel::Lanes8Avx512}) {
        std::vector<ProjectedPoint> batch(world.size());
        camera.projectPoints(world, batch, kernel);
        for (size_t i = 0; i < world.size(); ++i) {
            const ProjectedPoint one = camera.project(world[i]);
            EXPECT_EQ(batch[i].status, one.status);
            EXPECT_EQ(batch[i].pixel.x, one.pixel.x) << "same bits";
            EXPECT_EQ(batch[i].pixel.y, one.pixel.y) << "same bits";
        }
    }
}

// An OpenCV fisheye calibration of an ordinary lens: its polynomial keeps growing up to 121 degrees from the axis,
// but a calibration describes only the front hemisphere. Without a declared field a point behind the camera plane
// is clipped, as for a pinhole; declared as a 220-degree lens it gets the model's pixel.
TEST(WideFisheye, AnOrdinaryCalibrationSeesTheFrontHemisphereUnlessDeclaredWider)
{
    const std::array<double, 4> k{-0.013, -0.0037, 0.0016, -0.0004};
    ASSERT_GT(modelLimit(k), 120.0 * kDegree);
    std::mt19937_64 rng(90);
    for (double declared : {0.0, 220.0}) {
        CvCamera c;
        c.rvec = {uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3)};
        c.tvec = {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)};
        c.width = 1280;
        c.height = 800;
        c.fx = 331.2;
        c.fy = 330.7;
        c.cx = 640.4;
        c.cy = 399.8;
        c.distortion = {DistortionModel::Fisheye, {k[0], k[1], k[2], k[3]}, declared};
        const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne, 0.05, 1000.0);
        EXPECT_EQ(camera.seesBehind(), declared > 0.0);
        std::vector<glm::dvec3> world;
        for (int i = 0; i < 200; ++i) // in front up to 88 degrees, behind from 92 to 108 degrees
            world.push_back(pointAt(c, i % 2 ? uniform(rng, 92.0, 108.0) * kDegree : uniform(rng, 0.0, 88.0) * kDegree,
                                    uniform(rng, -M_PI, M_PI), uniform(rng, 0.5, 50.0)));
        int behind = 0;
        for (const glm::dvec3 &p : world) {
            const ProjectedPoint ours = camera.project(p);
            const glm::dvec3 o = opticalOf(c, p);
            if (o.z <= 0.0 && declared == 0.0) {
                EXPECT_EQ(ours.status, PointStatus::Clipped) << "behind the camera plane";
                ++behind;
                continue;
            }
            ASSERT_NE(ours.status, PointStatus::Clipped) << declared;
            EXPECT_LT(glm::length(ours.pixel - referencePixel(c, p)), 1e-7) << declared;
            if (o.z > 0.01 * glm::length(o)) {
                EXPECT_LT(glm::length(ours.pixel - test::cvProject(c, p)), 1e-6) << declared;
            }
        }
        EXPECT_EQ(behind, declared == 0.0 ? 100 : 0);
        expectBatchIsSinglePoint(camera, world);
    }
}

TEST(WideFisheye, TheValidFieldEndsWhereTheModelStopsGrowingNotAt89Degrees)
{
    std::mt19937_64 rng(21);
    for (const WideLens &lens : kLenses) {
        const CvCamera c = wideCamera(lens, rng, 359.99);
        const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne, 0.05, 1000.0);
        ASSERT_TRUE(camera.lens());
        const double limit = modelLimit(lens.k);
        EXPECT_GT(limit, 0.5 * lens.fovDeg * kDegree) << lens.fovDeg;
        EXPECT_NEAR(camera.lens()->validAngle(), limit, 0.011 * kDegree) << lens.fovDeg;
        EXPECT_LE(camera.lens()->validAngle(), limit + 1e-12) << "the turned part must never count as valid";
        EXPECT_TRUE(camera.seesBehind());
    }
}

// Declared narrower than the model's limit, the declared field decides: half of it from the axis.
TEST(WideFisheye, TheDeclaredFieldCapsTheModelsLimit)
{
    std::mt19937_64 rng(22);
    for (const WideLens &lens : kLenses) {
        const Camera camera = test::makeCamera(wideCamera(lens, rng), DepthRange::ZeroToOne, 0.05, 1000.0);
        EXPECT_NEAR(camera.lens()->validAngle(), std::min(modelLimit(lens.k), 0.5 * lens.fovDeg * kDegree),
                    0.011 * kDegree)
            << lens.fovDeg;
        EXPECT_TRUE(camera.seesBehind());
    }
}

// Points all round the field, in front and behind the camera plane, scalar and every batch loop, against the
// formula; and in front also against cv::fisheye::projectPoints.
TEST(WideFisheye, ProjectsBehindTheCameraPlaneAsTheModelSays)
{
    std::mt19937_64 rng(185);
    for (const WideLens &lens : kLenses) {
        for (DepthRange depth : {DepthRange::ZeroToOne, DepthRange::MinusOneToOne}) {
            const CvCamera c = wideCamera(lens, rng);
            const Camera camera = test::makeCamera(c, depth, 0.05, 1000.0);
            std::vector<glm::dvec3> world;
            for (int i = 0; i < 400; ++i) // half of them behind the camera plane
                world.push_back(pointAt(c, uniform(rng, i % 2 ? M_PI / 2 : 0.0, 0.5 * lens.fovDeg * kDegree),
                                        uniform(rng, -M_PI, M_PI), uniform(rng, 0.1, 50.0)));
            int behind = 0, visible = 0;
            for (const glm::dvec3 &p : world) {
                const ProjectedPoint ours = camera.project(p);
                ASSERT_NE(ours.status, PointStatus::Clipped) << lens.fovDeg;
                const glm::dvec2 expected = referencePixel(c, p);
                EXPECT_LT(glm::length(ours.pixel - expected), 1e-7) << lens.fovDeg;
                const glm::dvec3 o = opticalOf(c, p);
                behind += o.z < 0;
                visible += ours.status == PointStatus::Visible;
                if (o.z > 0.01 * glm::length(o)) {
                    EXPECT_LT(glm::length(ours.pixel - test::cvProject(c, p)), 1e-6) << lens.fovDeg;
                }
            }
            EXPECT_GE(behind, 200) << lens.fovDeg;
            EXPECT_GT(visible, 350) << lens.fovDeg;
            expectBatchIsSinglePoint(camera, world);
        }
    }
}

// Clipped: inside the near sphere (also behind the camera), beyond the model's limit, beyond the far plane.
TEST(WideFisheye, ClipsByTheNearSphereAndTheModelsLimit)
{
    std::mt19937_64 rng(200);
    for (const WideLens &lens : kLenses) {
        const CvCamera c = wideCamera(lens, rng);
        const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne, 0.5, 100.0);
        const double limit = camera.lens()->validAngle();
        for (int i = 0; i < 200; ++i) {
            const double phi = uniform(rng, -M_PI, M_PI);
            const double inside = uniform(rng, 0.0, limit - 0.001);
            EXPECT_EQ(camera.project(pointAt(c, inside, phi, 0.49)).status, PointStatus::Clipped) << "near sphere";
            EXPECT_NE(camera.project(pointAt(c, inside, phi, 0.51)).status, PointStatus::Clipped) << inside;
            if (limit < M_PI - 0.01) {
                EXPECT_EQ(camera.project(pointAt(c, uniform(rng, limit + 0.001, M_PI), phi, 5.0)).status,
                          PointStatus::Clipped)
                    << "past the model's limit";
            }
        }
        EXPECT_EQ(camera.project(pointAt(c, 0.1, 0.3, 101.0)).status, PointStatus::Clipped) << "beyond far";
        // Behind the camera, the far plane (a depth along the axis) never clips.
        EXPECT_NE(
            camera.project(pointAt(c, 0.5 * (M_PI / 2 + std::min(limit, 0.5 * lens.fovDeg * kDegree)), 0.3, 500.0))
                .status,
            PointStatus::Clipped);
    }
}

// Pixels -> rays, against the formula inverted here by bisection on theta and turned into the world by
// cv::Rodrigues; then the rays' points project back onto their pixels.
TEST(WideFisheye, UnprojectsRaysBehindTheCameraPlaneAndBack)
{
    std::mt19937_64 rng(220);
    for (const WideLens &lens : kLenses) {
        const CvCamera c = wideCamera(lens, rng);
        const Camera camera = test::makeCamera(c, DepthRange::MinusOneToOne, 0.05, 1000.0);
        cv::Matx33d rotation;
        cv::Rodrigues(c.rvec, rotation);
        const std::array<double, 4> k{c.distortion.coeffs[0], c.distortion.coeffs[1], c.distortion.coeffs[2],
                                      c.distortion.coeffs[3]};
        int behind = 0;
        for (int i = 0; i < 300; ++i) {
            const double angle = uniform(rng, i % 2 ? M_PI / 2 : 0.0, 0.5 * lens.fovDeg * kDegree);
            const double phi = uniform(rng, -M_PI, M_PI);
            const double td = thetaD(k, angle);
            const glm::dvec2 pixel(c.fx * td * std::cos(phi) + c.cx, c.fy * td * std::sin(phi) + c.cy);
            double lo = 0.0, hi = modelLimit(k);
            for (int j = 0; j < 200; ++j)
                (thetaD(k, 0.5 * (lo + hi)) < td ? lo : hi) = 0.5 * (lo + hi);
            const cv::Vec3d optical(std::sin(lo) * std::cos(phi), std::sin(lo) * std::sin(phi), std::cos(lo));
            const cv::Vec3d expected = rotation.t() * optical;
            auto ray = camera.unproject(pixel);
            ASSERT_TRUE(ray.ok()) << lens.fovDeg << " " << angle;
            for (int a = 0; a < 3; ++a)
                EXPECT_NEAR(ray->direction[a], expected[a], 1e-9) << lens.fovDeg << " " << angle;
            behind += angle > M_PI / 2;
            const ProjectedPoint back = camera.project(ray->origin + 7.0 * ray->direction);
            ASSERT_NE(back.status, PointStatus::Clipped);
            EXPECT_LT(glm::length(back.pixel - pixel), 1e-6);
        }
        EXPECT_GE(behind, 150);
        // Beyond the model's limit there is no ray.
        const double past = thetaD(k, camera.lens()->validAngle()) * 1.001;
        EXPECT_FALSE(camera.unproject({c.fx * past + c.cx, c.cy}).ok());
    }
}

// A segment passing behind the camera: its pieces in the field are drawn, each vertex on the formula's curve, and
// one that crosses the cone the lens cannot see (straight behind) is cut in two.
TEST(WideFisheye, SegmentsBehindTheCameraAreDrawnAndCutByTheBlindCone)
{
    std::mt19937_64 rng(2200);
    const WideLens &lens = kLenses[2];
    const CvCamera c = wideCamera(lens, rng, 359.99); // the model's limit, 121 degrees, bounds the cone
    const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne, 0.05, 1000.0);
    // In the optical frame: 2 m behind the camera, from left to right across the back axis.
    const glm::dvec3 a = test::worldFromOptical(c, {-20.0, 0.3, -2.0}),
                     b = test::worldFromOptical(c, {20.0, 0.3, -2.0});
    Polylines out;
    camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);
    ASSERT_EQ(out.size(), 2u) << "the blind cone about the back axis cuts the segment";
    cv::Matx33d rotation;
    cv::Rodrigues(c.rvec, rotation);
    int checked = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        for (const glm::dvec2 &vertex : out[i]) {
            // The vertex's ray meets the segment's line (y = 0.3, z = -2 in the optical frame). Right at the
            // cone's edge theta_d is flat (the model's limit), so a pixel there pins no angle: left out.
            auto ray = camera.unproject(vertex);
            ASSERT_TRUE(ray.ok());
            const cv::Vec3d d = rotation * cv::Vec3d(ray->direction.x, ray->direction.y, ray->direction.z);
            if (std::acos(d[2]) > camera.lens()->validAngle() - 0.5 * kDegree)
                continue;
            EXPECT_NEAR(d[1] / d[2], 0.3 / -2.0, 1e-6);
            ++checked;
        }
    }
    EXPECT_GT(checked, 20);
    EXPECT_LT(glm::length(out[0].front() - referencePixel(c, a)), 1e-6);
    EXPECT_LT(glm::length(out[1].back() - referencePixel(c, b)), 1e-6);
}

} // namespace
} // namespace overlayd
