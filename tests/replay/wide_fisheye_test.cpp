// SPDX-License-Identifier: Apache-2.0
// A 220-degree fisheye through the real binary: `overlayd project` puts points behind the camera plane where the
// OpenCV fisheye model, written out here on the angle (cv::fisheye cannot take z <= 0), puts them, and
// `overlayd unproject` turns those pixels back into the rays towards the points.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

// theta_d = theta (1 + k2 theta^4): grows up to 121 degrees from the axis (1 - 0.05 theta^4 = 0).
constexpr double kK2 = -0.01;
constexpr double kHalfFov = 110.0 * M_PI / 180.0;
const cv::Vec3d kRvec(2.0943951023931957, 0.0, 0.0), kTvec(0.0, 2.1650635094610964, 1.25);
constexpr double kCx = 801.5, kCy = 598.5;

double thetaD(double theta)
{
    return theta * (1.0 + kK2 * std::pow(theta, 4));
}

double focal()
{
    return 600.0 / thetaD(kHalfFov); // the 220-degree circle fills the image's height
}

std::string config()
{
    char text[1024];
    std::snprintf(text, sizeof text,
                  "[source]\nkind = \"synthetic\"\nwidth = 1600\nheight = 1200\n"
                  "[camera]\nrvec = [%.17g, 0.0, 0.0]\ntvec = [0.0, %.17g, %.17g]\nnear = 0.05\nfar = 100.0\n"
                  "[camera.pinhole]\nfx = %.17g\nfy = %.17g\ncx = %.17g\ncy = %.17g\nwidth = 1600\nheight = 1200\n"
                  "[camera.distortion]\nmodel = \"equidistant\"\ncoefficients = [0.0, %.17g, 0.0, 0.0]\n"
                  "max_field_deg = 220\n",
                  kRvec[0], kTvec[1], kTvec[2], focal(), focal(), kCx, kCy, kK2);
    return text;
}

cv::Matx33d rotation()
{
    cv::Matx33d r;
    cv::Rodrigues(kRvec, r);
    return r;
}

// The world point `distance` from the camera at `angle` from its axis, azimuth phi.
cv::Vec3d pointAt(double angle, double phi, double distance)
{
    const cv::Vec3d optical(distance * std::sin(angle) * std::cos(phi), distance * std::sin(angle) * std::sin(phi),
                            distance * std::cos(angle));
    return rotation().t() * (optical - kTvec);
}

cv::Point2d formulaPixel(const cv::Vec3d &world)
{
    const cv::Vec3d o = rotation() * world + kTvec;
    const double r = std::hypot(o[0], o[1]), td = thetaD(std::atan2(r, o[2]));
    return {focal() * td * o[0] / r + kCx, focal() * td * o[1] / r + kCy};
}

// Numbers after each `"key":[` in the output, n per occurrence (NaN for null).
std::vector<std::vector<double>> arraysAfter(const std::string &out, const std::string &key, int n)
{
    std::vector<std::vector<double>> result;
    const std::string marker = "\"" + key + "\":";
    for (size_t at = out.find(marker); at != std::string::npos; at = out.find(marker, at + 1)) {
        std::vector<double> v(n, NAN);
        if (out[at + marker.size()] == '[') {
            const char *p = out.c_str() + at + marker.size() + 1;
            for (int i = 0; i < n; ++i) {
                char *end = nullptr;
                v[i] = std::strtod(p, &end);
                p = end + 1;
            }
        }
        result.push_back(v);
    }
    return result;
}

TEST(WideFisheye, ProjectAndUnprojectSeeBehindTheCameraPlane)
{
    const std::string dir = scratchDir("wide-fisheye");
    writeFile(dir + "/fisheye.toml", config());
    std::vector<cv::Point3d> world;
    for (int i = 0; i < 24; ++i) // from the axis out to the edge of the 220-degree circle, behind from 90 degrees
        world.push_back(pointAt(kHalfFov * (i + 0.5) / 24.0, 0.7 * i, 1.0 + 0.3 * i));
    const RunResult project = runOverlayd("project --config fisheye.toml --json --" + pointArguments(world), dir);
    ASSERT_EQ(project.exitStatus, 0) << project.all();
    const auto pixels = arraysAfter(project.out, "pixel", 2);
    ASSERT_EQ(pixels.size(), world.size()) << project.out;
    std::string pixelArgs = "unproject --config fisheye.toml --json --";
    int behind = 0;
    for (size_t i = 0; i < world.size(); ++i) {
        const cv::Point2d expected = formulaPixel(cv::Vec3d(world[i]));
        EXPECT_LT(cv::norm(cv::Point2d(pixels[i][0], pixels[i][1]) - expected), 1e-6) << i << "\n" << project.out;
        behind += (rotation() * cv::Vec3d(world[i]) + kTvec)[2] < 0.0;
        char number[64];
        std::snprintf(number, sizeof number, " %.17g %.17g", pixels[i][0], pixels[i][1]);
        pixelArgs += number;
    }
    EXPECT_GE(behind, 4);
    EXPECT_EQ(project.out.find("\"reason\":\"behind-camera\""), std::string::npos) << project.out;

    const RunResult unproject = runOverlayd(pixelArgs, dir);
    ASSERT_EQ(unproject.exitStatus, 0) << unproject.all();
    const auto origins = arraysAfter(unproject.out, "origin", 3);
    const auto directions = arraysAfter(unproject.out, "direction", 3);
    ASSERT_EQ(directions.size(), world.size()) << unproject.out;
    const cv::Vec3d eye = -(rotation().t() * kTvec);
    for (size_t i = 0; i < world.size(); ++i) {
        const cv::Vec3d towards = cv::normalize(cv::Vec3d(world[i]) - eye);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(origins[i][k], eye[k], 1e-9) << i;
            EXPECT_NEAR(directions[i][k], towards[k], 1e-7) << i << "\n" << unproject.out;
        }
    }
}

// What the lens cannot see is said: past the model's 121 degrees, and inside the near sphere behind the camera.
TEST(WideFisheye, ProjectSaysWhyAPointHasNoPixel)
{
    const std::string dir = scratchDir("wide-fisheye-reasons");
    writeFile(dir + "/fisheye.toml", config());
    const cv::Vec3d past = pointAt(130.0 * M_PI / 180.0, 0.3, 2.0), near = pointAt(100.0 * M_PI / 180.0, 0.3, 0.04);
    char args[512];
    std::snprintf(args, sizeof args, "project --config fisheye.toml --json -- %.17g %.17g %.17g %.17g %.17g %.17g",
                  past[0], past[1], past[2], near[0], near[1], near[2]);
    const RunResult run = runOverlayd(args, dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    const size_t circle = run.out.find("\"reason\":\"outside-image-circle\"");
    const size_t beforeNear = run.out.find("\"reason\":\"before-near\"");
    EXPECT_NE(circle, std::string::npos) << run.out;
    EXPECT_NE(beforeNear, std::string::npos) << run.out;
    EXPECT_LT(circle, beforeNear) << run.out;
}

} // namespace
} // namespace overlayd::test
