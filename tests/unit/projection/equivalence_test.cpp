// SPDX-License-Identifier: Apache-2.0
// equivalence_test: every description of the same camera (intrinsics forms, pose forms) gives the same pixels.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "projection/camera.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/viewport.h"

using namespace overlayd;

namespace {

constexpr double kPixelTolerance = 1e-9;

// One calibrated camera: what every intrinsics form below describes.
struct Intrinsics {
    int width, height;
    double fx, fy, cx, cy;
};

// A pose shared by all cameras of the intrinsics tests: at (1, -2, 1.5), looking at the origin, world Z up.
Pose referencePose()
{
    auto pose = poseLookAt({1.0, -2.0, 1.5}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
    EXPECT_TRUE(pose.ok());
    return *pose;
}

Viewport topLeftViewport(int width, int height)
{
    auto viewport = Viewport::create({width, height});
    EXPECT_TRUE(viewport.ok());
    return *viewport;
}

Camera makeCamera(const Pose &pose, const Result<Projection> &projection, const Viewport &viewport)
{
    EXPECT_TRUE(projection.ok()) << projection.error().message;
    auto camera = Camera::create(pose, *projection, Distortion{}, viewport);
    EXPECT_TRUE(camera.ok()) << camera.error().message;
    return *camera;
}

// World points spread through the view volume of referencePose(), some off the image.
std::vector<glm::dvec3> samplePoints()
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> box(-1.0, 1.0);
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 200; ++i)
        points.push_back({box(rng), box(rng), box(rng)});
    return points;
}

// The independent reference: OpenCV's projectPoints with K and the optical-frame extrinsics of the same pose.
std::vector<glm::dvec2> openCvPixels(const Intrinsics &k, const Pose &pose, const std::vector<glm::dvec3> &points)
{
    // x_optical = diag(1, -1, -1) x_internal: the OpenGL camera frame and OpenCV's share x, flip y and z.
    cv::Matx33d r;
    cv::Vec3d t;
    for (int row = 0; row < 3; ++row) {
        const double flip = row == 0 ? 1.0 : -1.0;
        for (int col = 0; col < 3; ++col)
            r(row, col) = flip * pose.rotation[col][row];
        t[row] = flip * pose.translation[row];
    }
    cv::Vec3d rvec;
    cv::Rodrigues(r, rvec);
    const cv::Matx33d kMatrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
    std::vector<cv::Point3d> objects;
    for (const glm::dvec3 &p : points)
        objects.emplace_back(p.x, p.y, p.z);
    std::vector<cv::Point2d> image;
    cv::projectPoints(objects, rvec, t, kMatrix, cv::noArray(), image);
    std::vector<glm::dvec2> pixels;
    for (const cv::Point2d &p : image)
        pixels.push_back({p.x, p.y});
    return pixels;
}

// The frustum bounds on the near plane of the image of k: its outer edges are pixel centres -/+ 0.5.
FrustumBounds boundsOf(const Intrinsics &k, double near, double far)
{
    // Optical x = (u - cx) / fx; the internal y axis is the optical y axis flipped.
    return {near * (-0.5 - k.cx) / k.fx,
            near * (k.width - 0.5 - k.cx) / k.fx,
            -near * (k.height - 0.5 - k.cy) / k.fy,
            near * (0.5 + k.cy) / k.fy,
            near,
            far};
}

// The viewing pipeline's window at distance focal: the same frustum scaled from the near plane to the window plane.
WindowIntrinsics windowOf(const Intrinsics &k, double focal, double near, double far)
{
    const FrustumBounds b = boundsOf(k, near, far);
    const double s = focal / near;
    return {focal,
            {s * (b.left + b.right) / 2.0, s * (b.bottom + b.top) / 2.0},
            s * (b.right - b.left) / 2.0,
            s * (b.top - b.bottom) / 2.0,
            near,
            far};
}

struct Form {
    std::string name;
    Result<Projection> projection;
};

std::vector<Form> formsOf(const Intrinsics &k, double near, double far, DepthRange depth, bool centred)
{
    std::vector<Form> forms;
    forms.push_back(
        {"pinhole", Projection::pinhole({k.fx, k.fy, k.cx, k.cy, 0.0, k.width, k.height}, near, far, depth)});
    forms.push_back({"frustum", Projection::frustum(boundsOf(k, near, far), depth)});
    forms.push_back({"window focal 1", Projection::window(windowOf(k, 1.0, near, far), depth)});
    forms.push_back({"window focal 37", Projection::window(windowOf(k, 37.0, near, far), depth)});
    if (centred) {
        // The fov form describes a window centred on the optical axis with square pixels only.
        const double fovy = 2.0 * std::atan(k.height / 2.0 / k.fy) * 180.0 / M_PI;
        const double fovx = 2.0 * std::atan(k.width / 2.0 / k.fx) * 180.0 / M_PI;
        const double aspect = double(k.width) / k.height;
        forms.push_back({"fov vertical", Projection::perspective(FovAxis::Vertical, fovy, aspect, near, far, depth)});
        forms.push_back(
            {"fov horizontal", Projection::perspective(FovAxis::Horizontal, fovx, aspect, near, far, depth)});
    }
    return forms;
}

void expectAllFormsAgree(const Intrinsics &k, bool centred)
{
    const Pose pose = referencePose();
    const Viewport viewport = topLeftViewport(k.width, k.height);
    const std::vector<glm::dvec3> points = samplePoints();
    const std::vector<glm::dvec2> reference = openCvPixels(k, pose, points);
    const double near = 0.05, far = 40.0;
    for (DepthRange depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        const std::vector<Form> forms = formsOf(k, near, far, depth, centred);
        std::vector<Camera> cameras;
        for (const Form &form : forms)
            cameras.push_back(makeCamera(pose, form.projection, viewport));
        for (std::size_t i = 0; i < points.size(); ++i) {
            const ProjectedPoint first = cameras[0].project(points[i]);
            ASSERT_NE(first.status, PointStatus::Clipped) << "point " << i;
            EXPECT_NEAR(first.pixel.x, reference[i].x, kPixelTolerance) << "pinhole vs OpenCV, point " << i;
            EXPECT_NEAR(first.pixel.y, reference[i].y, kPixelTolerance) << "pinhole vs OpenCV, point " << i;
            for (std::size_t f = 1; f < forms.size(); ++f) {
                const ProjectedPoint p = cameras[f].project(points[i]);
                ASSERT_EQ(p.status, first.status) << forms[f].name << ", point " << i;
                EXPECT_NEAR(p.pixel.x, reference[i].x, kPixelTolerance) << forms[f].name << ", point " << i;
                EXPECT_NEAR(p.pixel.y, reference[i].y, kPixelTolerance) << forms[f].name << ", point " << i;
                // Same near and far planes: the same depth too.
                EXPECT_NEAR(p.depth, first.depth, 1e-9) << forms[f].name << ", point " << i;
            }
        }
    }
}

TEST(Equivalence, CentredCameraAllIntrinsicsFormsGiveTheSamePixels)
{
    // Principal point at the image centre: pixel centres run 0..W-1, so the centre is (W-1)/2.
    expectAllFormsAgree({640, 480, 500.0, 500.0, 319.5, 239.5}, true);
}

TEST(Equivalence, OffAxisCameraWindowFrustumAndPinholeGiveTheSamePixels)
{
    // A principal point well away from the centre (a shifted lens, or a crop): no fov describes it.
    expectAllFormsAgree({640, 480, 520.0, 515.0, 250.25, 300.75}, false);
    expectAllFormsAgree({1920, 1080, 1400.0, 1380.0, 1100.0, 400.0}, false);
}

TEST(Equivalence, SkewedPinholeMatchesTheCameraMatrixWrittenOut)
{
    // OpenCV's projectPoints ignores K's skew entry, so the reference is K applied by hand: u = fx x + s y + cx.
    const PinholeIntrinsics k{600.0, 580.0, 330.0, 250.0, 12.0, 640, 480};
    const Pose pose = referencePose();
    for (DepthRange depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        const Camera camera = makeCamera(pose, Projection::pinhole(k, 0.05, 40.0, depth), topLeftViewport(640, 480));
        for (const glm::dvec3 &world : samplePoints()) {
            const glm::dvec3 internal = pose.rotation * world + pose.translation;
            const double x = internal.x / -internal.z, y = -internal.y / -internal.z; // optical x, y
            const ProjectedPoint p = camera.project(world);
            ASSERT_NE(p.status, PointStatus::Clipped);
            EXPECT_NEAR(p.pixel.x, k.fx * x + k.skew * y + k.cx, kPixelTolerance);
            EXPECT_NEAR(p.pixel.y, k.fy * y + k.cy, kPixelTolerance);
        }
    }
}

// --- Pose forms --------------------------------------------------------------------------------------------------

// One camera for all pose forms: at eye, yaw 30 degrees, pitched down by 20 degrees, no roll, world Z up.
constexpr double kYawDeg = 30.0, kPitchDeg = 20.0;
const glm::dvec3 kEye{2.0, -1.0, 3.0};

// The camera's axes in world coordinates, written out from the angles: forward, left (body y), up (body z).
glm::dvec3 forwardAxis()
{
    const double yaw = kYawDeg * M_PI / 180.0, pitch = kPitchDeg * M_PI / 180.0;
    return {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), -std::sin(pitch)};
}
glm::dvec3 leftAxis()
{
    const double yaw = kYawDeg * M_PI / 180.0;
    return {-std::sin(yaw), std::cos(yaw), 0.0};
}
glm::dvec3 upAxis()
{
    return glm::cross(forwardAxis(), leftAxis());
}

std::vector<std::pair<std::string, Result<Pose>>> allPoseForms()
{
    const glm::dvec3 forward = forwardAxis(), left = leftAxis(), up = upAxis();
    const glm::dvec3 worldUp{0.0, 0.0, 1.0};
    std::vector<std::pair<std::string, Result<Pose>>> poses;
    poses.emplace_back("lookAt", poseLookAt(kEye, kEye + 7.0 * forward, worldUp));
    poses.emplace_back("gaze", poseFromGaze(kEye, 0.5 * forward, worldUp));
    // The viewing pipeline: VPN points back towards the viewer, and VUP need not be perpendicular to it.
    poses.emplace_back("prp/vpn/vup", poseFromPrpVpnVup(kEye, -3.0 * forward, worldUp + 0.3 * forward));
    poses.emplace_back("yaw/pitch/roll", poseFromYawPitchRoll(kEye, kYawDeg, kPitchDeg, 0.0));

    // world_from_axes for each axes convention, as GLM's quaternion of the matrix whose columns are the axes.
    poses.emplace_back("orientation body",
                       poseFromOrientation(kEye, glm::quat_cast(glm::dmat3(forward, left, up)), CameraAxes::Body));
    poses.emplace_back("orientation optical",
                       poseFromOrientation(kEye, glm::quat_cast(glm::dmat3(-left, -up, forward)), CameraAxes::Optical));
    poses.emplace_back("orientation opengl",
                       poseFromOrientation(kEye, glm::quat_cast(glm::dmat3(-left, up, -forward)), CameraAxes::OpenGl));

    // OpenCV extrinsics: the rows of R are the optical axes (right, down, forward) in world coordinates.
    const glm::dmat3 r = glm::transpose(glm::dmat3(-left, -up, forward));
    const glm::dvec3 t = -(r * kEye);
    poses.emplace_back("R, t", poseFromRt(r, t));
    cv::Matx33d rCv;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            rCv(row, col) = r[col][row];
    cv::Vec3d rvec;
    cv::Rodrigues(rCv, rvec);
    poses.emplace_back("rvec, tvec", poseFromRodrigues({rvec[0], rvec[1], rvec[2]}, t));
    return poses;
}

TEST(Equivalence, AllPoseFormsGiveTheSameViewMatrix)
{
    // Reference: the viewing pipeline's M_cam = [u v w e]^-1 with u right, v up, w backwards, inverted by GLM.
    const glm::dmat4 cameraToWorld(glm::dvec4(-leftAxis(), 0.0), glm::dvec4(upAxis(), 0.0),
                                   glm::dvec4(-forwardAxis(), 0.0), glm::dvec4(kEye, 1.0));
    const glm::dmat4 expected = glm::inverse(cameraToWorld);
    for (const auto &[name, pose] : allPoseForms()) {
        ASSERT_TRUE(pose.ok()) << name << ": " << pose.error().message;
        const glm::dmat4 view = pose->viewMatrix();
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(view[c][r], expected[c][r], 1e-12) << name << " m[" << c << "][" << r << "]";
    }
}

TEST(Equivalence, AllPoseFormsGiveTheSamePixels)
{
    const Intrinsics k{800, 600, 650.0, 650.0, 420.0, 290.0};
    const Viewport viewport = topLeftViewport(k.width, k.height);
    auto projection =
        Projection::pinhole({k.fx, k.fy, k.cx, k.cy, 0.0, k.width, k.height}, 0.1, 100.0, DepthRange::ZeroToOne);
    // Points in front of the camera, around its optical axis.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> spread(-2.0, 2.0), distance(1.0, 20.0);
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 100; ++i)
        points.push_back(kEye + distance(rng) * forwardAxis() + spread(rng) * leftAxis() + spread(rng) * upAxis());

    auto lookAt = poseLookAt(kEye, kEye + forwardAxis(), {0.0, 0.0, 1.0});
    ASSERT_TRUE(lookAt.ok());
    const std::vector<glm::dvec2> reference = openCvPixels(k, *lookAt, points);
    for (const auto &[name, pose] : allPoseForms()) {
        ASSERT_TRUE(pose.ok()) << name;
        const Camera camera = makeCamera(*pose, projection, viewport);
        for (std::size_t i = 0; i < points.size(); ++i) {
            const ProjectedPoint p = camera.project(points[i]);
            ASSERT_NE(p.status, PointStatus::Clipped) << name << ", point " << i;
            EXPECT_NEAR(p.pixel.x, reference[i].x, kPixelTolerance) << name << ", point " << i;
            EXPECT_NEAR(p.pixel.y, reference[i].y, kPixelTolerance) << name << ", point " << i;
        }
    }
}

TEST(Equivalence, RotationFromRodriguesEqualsOpenCvRodrigues)
{
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> component(-3.0, 3.0);
    std::vector<glm::dvec3> rvecs{{0, 0, 0}, {1e-9, 0, 0}, {0, M_PI, 0}, {0, 0, -M_PI / 2}};
    for (int i = 0; i < 200; ++i)
        rvecs.push_back({component(rng), component(rng), component(rng)});
    for (const glm::dvec3 &rvec : rvecs) {
        cv::Matx33d expected;
        cv::Rodrigues(cv::Vec3d(rvec.x, rvec.y, rvec.z), expected);
        const glm::dmat3 actual = rotationFromRodrigues(rvec);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col)
                EXPECT_NEAR(actual[col][row], expected(row, col), 1e-12)
                    << "rvec (" << rvec.x << ", " << rvec.y << ", " << rvec.z << ") R(" << row << "," << col << ")";
    }
}

} // namespace
