// SPDX-License-Identifier: Apache-2.0
// Test helpers: random OpenCV-style cameras, and their projections computed by OpenCV itself as the reference.
//
// Everything here that produces an expected value goes through OpenCV (cv::Rodrigues, cv::projectPoints,
// cv::fisheye::projectPoints), never through overlayd, so the tests compare two independent implementations.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "projection/camera.h"

namespace overlayd::test {

// One calibrated camera as OpenCV describes it: x_optical = R(rvec) x_world + tvec, then K and distortion.
struct CvCamera {
    cv::Vec3d rvec, tvec;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    int width = 0, height = 0;
    Distortion distortion;

    cv::Matx33d cameraMatrix() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
    std::vector<double> distCoeffs() const
    {
        return {distortion.coeffs.begin(), distortion.coeffs.begin() + coefficientCount(distortion.model)};
    }
    PinholeIntrinsics intrinsics() const { return {fx, fy, cx, cy, 0.0, width, height}; }
};

inline double uniform(std::mt19937_64 &rng, double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Coefficients in the range real calibrations produce, strong enough that a wrong term shows at 1e-6 px.
inline Distortion randomDistortion(std::mt19937_64 &rng, DistortionModel model)
{
    Distortion d;
    d.model = model;
    switch (model) {
    case DistortionModel::None:
        break;
    case DistortionModel::Rational:
        d.coeffs[5] = uniform(rng, -0.2, 0.2);
        d.coeffs[6] = uniform(rng, -0.05, 0.05);
        d.coeffs[7] = uniform(rng, -0.02, 0.02);
        [[fallthrough]];
    case DistortionModel::RadialTangential:
        d.coeffs[0] = uniform(rng, -0.3, 0.3);
        d.coeffs[1] = uniform(rng, -0.1, 0.1);
        d.coeffs[2] = uniform(rng, -2e-3, 2e-3);
        d.coeffs[3] = uniform(rng, -2e-3, 2e-3);
        d.coeffs[4] = uniform(rng, -0.02, 0.02);
        break;
    case DistortionModel::Fisheye:
        d.coeffs[0] = uniform(rng, -0.05, 0.1);
        d.coeffs[1] = uniform(rng, -0.02, 0.02);
        d.coeffs[2] = uniform(rng, -0.01, 0.01);
        d.coeffs[3] = uniform(rng, -0.005, 0.005);
        break;
    }
    return d;
}

inline CvCamera randomCvCamera(std::mt19937_64 &rng, DistortionModel model)
{
    CvCamera c;
    c.rvec = {uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -3, 3)};
    c.tvec = {uniform(rng, -20, 20), uniform(rng, -20, 20), uniform(rng, -20, 20)};
    c.width = std::uniform_int_distribution<int>(64, 4096)(rng);
    c.height = std::uniform_int_distribution<int>(48, 3072)(rng);
    // Fisheye lenses have short focal lengths for their image size; pinholes anything from wide to tele.
    c.fx = c.width * (model == DistortionModel::Fisheye ? uniform(rng, 0.2, 0.5) : uniform(rng, 0.4, 3.0));
    c.fy = c.fx * uniform(rng, 0.95, 1.05);
    c.cx = c.width * uniform(rng, 0.4, 0.6);
    c.cy = c.height * uniform(rng, 0.4, 0.6);
    c.distortion = randomDistortion(rng, model);
    return c;
}

// World point from a point given in the camera's optical frame: x_world = R^T (x_optical - t), R from OpenCV.
inline glm::dvec3 worldFromOptical(const CvCamera &c, const glm::dvec3 &optical)
{
    cv::Matx33d r;
    cv::Rodrigues(c.rvec, r);
    const cv::Vec3d w = r.t() * (cv::Vec3d(optical.x, optical.y, optical.z) - c.tvec);
    return {w[0], w[1], w[2]};
}

// The camera-space depth (optical z) of a world point, by OpenCV's rotation.
inline double opticalDepth(const CvCamera &c, const glm::dvec3 &world)
{
    cv::Matx33d r;
    cv::Rodrigues(c.rvec, r);
    return (r * cv::Vec3d(world.x, world.y, world.z) + c.tvec)[2];
}

// OpenCV's pixels for world points: cv::fisheye::projectPoints for the fisheye model, cv::projectPoints otherwise.
inline std::vector<glm::dvec2> cvProject(const CvCamera &c, const std::vector<glm::dvec3> &world)
{
    std::vector<cv::Point3d> object;
    object.reserve(world.size());
    for (const glm::dvec3 &p : world)
        object.emplace_back(p.x, p.y, p.z);
    std::vector<cv::Point2d> image;
    if (c.distortion.model == DistortionModel::Fisheye) {
        const cv::Vec4d d(c.distortion.coeffs[0], c.distortion.coeffs[1], c.distortion.coeffs[2],
                          c.distortion.coeffs[3]);
        cv::fisheye::projectPoints(object, image, c.rvec, c.tvec, c.cameraMatrix(), d);
    } else {
        cv::projectPoints(object, c.rvec, c.tvec, c.cameraMatrix(), c.distCoeffs(), image);
    }
    std::vector<glm::dvec2> pixels;
    pixels.reserve(image.size());
    for (const cv::Point2d &p : image)
        pixels.emplace_back(p.x, p.y);
    return pixels;
}

inline glm::dvec2 cvProject(const CvCamera &c, const glm::dvec3 &world)
{
    return cvProject(c, std::vector<glm::dvec3>{world})[0];
}

// Our camera for the same calibration: top-left origin, a viewport the size of the image.
inline Camera makeCamera(const CvCamera &c, DepthRange depth, double near = 1e-3, double far = 1e6,
                         const ViewportSpec *viewportSpec = nullptr)
{
    auto pose = poseFromRodrigues({c.rvec[0], c.rvec[1], c.rvec[2]}, {c.tvec[0], c.tvec[1], c.tvec[2]});
    EXPECT_TRUE(pose.ok());
    auto projection = Projection::pinhole(c.intrinsics(), near, far, depth);
    EXPECT_TRUE(projection.ok()) << (projection.ok() ? "" : projection.error().message);
    auto viewport = Viewport::create(viewportSpec ? *viewportSpec : ViewportSpec{c.width, c.height});
    EXPECT_TRUE(viewport.ok());
    auto camera = Camera::create(*pose, *projection, c.distortion, *viewport);
    EXPECT_TRUE(camera.ok()) << (camera.ok() ? "" : camera.error().message);
    return std::move(camera).value();
}

// The largest normalized radius (optical x/z, y/z) random test points may use: well inside the lens's valid
// field (where its mapping still increases) and at most 80 degrees off-axis.
inline double testFieldRadius(const Camera &camera)
{
    const double limit = std::tan(80.0 * M_PI / 180.0);
    return camera.lens() ? std::min(0.9 * camera.lens()->validRadius(), limit) : limit;
}

// A random point in the optical frame, in front of the camera at depth [zMin, zMax], within normalized radius.
inline glm::dvec3 randomOpticalPoint(std::mt19937_64 &rng, double radius, double zMin, double zMax)
{
    // Uniform in the disc of the normalized image plane, so the outer field is exercised as often as the centre.
    const double r = radius * std::sqrt(uniform(rng, 0.0, 1.0));
    const double phi = uniform(rng, -M_PI, M_PI);
    const double z = uniform(rng, zMin, zMax);
    return {r * std::cos(phi) * z, r * std::sin(phi) * z, z};
}

inline const char *modelName(DistortionModel model)
{
    switch (model) {
    case DistortionModel::None:
        return "None";
    case DistortionModel::RadialTangential:
        return "RadialTangential";
    case DistortionModel::Rational:
        return "Rational";
    case DistortionModel::Fisheye:
        return "Fisheye";
    }
    return "?";
}

} // namespace overlayd::test
