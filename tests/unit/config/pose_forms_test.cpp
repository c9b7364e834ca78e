// SPDX-License-Identifier: Apache-2.0
// Every pose form of [camera] describes the same physical camera; each must project like cv::projectPoints with
// a rotation and translation written down by hand.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

// The camera: at C = (1, -5, 2), looking along +Y and pitched 30 degrees down (Z up). Its optical axes in world
// coordinates, by hand: x right = (1, 0, 0), y down = (0, -sin30, -cos30), z forward = (0, cos30, -sin30).
const double kC30 = std::sqrt(3.0) / 2.0, kS30 = 0.5;
const cv::Matx33d kR(1, 0, 0, 0, -kS30, -kC30, 0, kC30, -kS30); // rows: the optical axes
const cv::Vec3d kCentre(1, -5, 2);
const cv::Matx33d kK(800, 0, 639.5, 0, 800, 359.5, 0, 0, 1);

cv::Vec3d tvec()
{
    return -(kR * kCentre);
}

std::string configWithPose(const std::string &poseKeys, const std::string &frames = "")
{
    return R"(
[source]
width = 1280
height = 720
)" + frames +
           R"(
[camera]
)" + poseKeys +
           R"(
[camera.pinhole]
fx = 800
fy = 800
cx = 639.5
cy = 359.5
width = 1280
height = 720
)";
}

std::string vec(const cv::Vec3d &v)
{
    char text[128];
    std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
    return text;
}

void expectMatchesOpenCv(const std::string &toml)
{
    const DaemonConfig config = loadValid(toml);
    auto camera = config.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    const std::vector<cv::Point3d> world{{0, 0, 0}, {1, 0, 0}, {2, 3, 0}, {-1, 2, 1}, {1, -1, 1.5}, {4, 10, 0}};
    const auto expected = opencvProject(world, kR, tvec(), kK, {});
    for (size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint p = camera->project(glm::dvec3(world[i].x, world[i].y, world[i].z));
        ASSERT_NE(p.status, PointStatus::Clipped) << "point " << i;
        EXPECT_NEAR(p.pixel.x, expected[i].x, 1e-6) << "point " << i;
        EXPECT_NEAR(p.pixel.y, expected[i].y, 1e-6) << "point " << i;
    }
}

const cv::Vec3d kForward(0, kC30, -kS30);

TEST(PoseForms, EyeTargetUp)
{
    expectMatchesOpenCv(
        configWithPose("eye = " + vec(kCentre) + "\ntarget = " + vec(kCentre + 3.0 * kForward) + "\nup = [0, 0, 1]"));
}

TEST(PoseForms, EyeGazeUpDefaultsUpToZ)
{
    expectMatchesOpenCv(configWithPose("eye = " + vec(kCentre) + "\ngaze = " + vec(2.0 * kForward)));
}

TEST(PoseForms, PrpVpnVup)
{
    // VPN points back towards the viewer.
    expectMatchesOpenCv(configWithPose("prp = " + vec(kCentre) + "\nvpn = " + vec(-kForward) + "\nvup = [0, 0, 1]"));
}

TEST(PoseForms, QuaternionOpticalAxes)
{
    // world_from_optical is a rotation of -120 degrees about X: q = [cos(-60), sin(-60), 0, 0].
    expectMatchesOpenCv(configWithPose("position = " + vec(kCentre) +
                                       "\norientation = [0.5, -0.86602540378443865, 0, 0]\naxes = \"optical\""));
}

TEST(PoseForms, QuaternionBodyAxesIsTheDefault)
{
    // world_from_body = Rz(90) Ry(30): q = [c45 c15, -s45 s15, c45 s15, s45 c15].
    const double c45 = std::cos(M_PI / 4), s45 = std::sin(M_PI / 4), c15 = std::cos(M_PI / 12),
                 s15 = std::sin(M_PI / 12);
    char q[160];
    std::snprintf(q, sizeof q, "[%.17g, %.17g, %.17g, %.17g]", c45 * c15, -s45 * s15, c45 * s15, s45 * c15);
    expectMatchesOpenCv(configWithPose("position = " + vec(kCentre) + "\norientation = " + q));
}

TEST(PoseForms, QuaternionOpenGlAxes)
{
    // world_from_opengl is a rotation of 60 degrees about X.
    expectMatchesOpenCv(configWithPose("position = " + vec(kCentre) +
                                       "\norientation = [0.86602540378443865, 0.5, 0, 0]\naxes = \"opengl\""));
}

TEST(PoseForms, YawPitchRollDegrees)
{
    expectMatchesOpenCv(configWithPose("position = " + vec(kCentre) + "\nyaw = 90\npitch = 30\nroll = 0"));
}

TEST(PoseForms, OpenCvRvecTvec)
{
    // R is a rotation of 120 degrees about X.
    expectMatchesOpenCv(configWithPose("rvec = [2.0943951023931957, 0, 0]\ntvec = " + vec(tvec())));
}

TEST(PoseForms, OpenCvRmatTvec)
{
    char rows[256];
    std::snprintf(rows, sizeof rows, "rmat = [[1, 0, 0], [0, %.17g, %.17g], [0, %.17g, %.17g]]", -kS30, -kC30, kC30,
                  -kS30);
    expectMatchesOpenCv(configWithPose(std::string(rows) + "\ntvec = " + vec(tvec())));
}

TEST(PoseForms, CameraMountedOnAFrame)
{
    // The rig's x axis is the world's y; in the rig the camera looks along x, 2 m up.
    const std::string rig = "[[frame]]\nname = \"rig\"\ntranslation = [1, -5, 0]\nyaw = 90\n";
    expectMatchesOpenCv(configWithPose("frame = \"rig\"\nposition = [0, 0, 2]\npitch = 30", rig));
}

TEST(PoseForms, CameraMountedOnAScaledChildFrame)
{
    // Scale 2: the camera's 1 m up in the child is 2 m in the world; pixels do not change with uniform scale.
    const std::string frames = "[[frame]]\nname = \"child\"\nparent = \"rig\"\nscale = 2.0\n"
                               "[[frame]]\nname = \"rig\"\ntranslation = [1, -5, 0]\nrotation = "
                               "[0.70710678118654757, 0, 0, 0.70710678118654757]\n";
    expectMatchesOpenCv(configWithPose("frame = \"child\"\nposition = [0, 0, 1]\npitch = 30", frames));
}

} // namespace
} // namespace overlayd::test
