// SPDX-License-Identifier: Apache-2.0
// bad_input_test: every degenerate input is refused with its documented ErrorCode and a message, never a NaN.
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/viewport.h"

using namespace overlayd;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const glm::dvec3 kX{1, 0, 0}, kY{0, 1, 0}, kZ{0, 0, 1}, kZero{0, 0, 0};

template<typename T>
::testing::AssertionResult fails(const Result<T> &result, ErrorCode code)
{
    if (result.ok())
        return ::testing::AssertionFailure() << "accepted; expected " << errorCodeName(code);
    if (result.error().code != code)
        return ::testing::AssertionFailure() << errorCodeName(result.error().code) << " (" << result.error().message
                                             << "); expected " << errorCodeName(code);
    if (result.error().message.empty())
        return ::testing::AssertionFailure() << errorCodeName(code) << " with an empty message";
    return ::testing::AssertionSuccess();
}

bool finite(const glm::dmat4 &m)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                return false;
    return true;
}

// --- Poses --------------------------------------------------------------------------------------------------------

TEST(BadInput, UpParallelToGaze)
{
    EXPECT_TRUE(fails(poseLookAt(kZero, {0, 0, 5}, kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseLookAt(kZero, {0, 0, 5}, -3.0 * kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseFromGaze(kZero, {1, 2, 3}, {2, 4, 6}), ErrorCode::DegenerateBasis));
    // Parallel up to rounding is as degenerate as exactly parallel.
    EXPECT_TRUE(fails(poseFromGaze(kZero, kZ, {1e-13, 0, 1}), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseFromPrpVpnVup(kZero, kZ, -kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(
        fails(poseFromPrpVpnVup(kZero, {1, 1, 0}, glm::dvec3(2 + 1e-14, 2, 1e-14)), ErrorCode::DegenerateBasis));
}

TEST(BadInput, ZeroVectorsAndCoincidentPoints)
{
    EXPECT_TRUE(fails(poseFromGaze(kZero, kZero, kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseFromGaze(kZero, kX, kZero), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseLookAt({1, 2, 3}, {1, 2, 3}, kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseLookAt(kZero, kX, kZero), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseFromPrpVpnVup(kZero, kZero, kZ), ErrorCode::DegenerateBasis));
    EXPECT_TRUE(fails(poseFromPrpVpnVup(kZero, kZ, kZero), ErrorCode::DegenerateBasis));
}

TEST(BadInput, NonFinitePoseInputs)
{
    EXPECT_TRUE(fails(poseLookAt({kNaN, 0, 0}, kX, kZ), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseLookAt(kZero, {kInf, 0, 0}, kZ), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseLookAt(kZero, kX, {0, 0, kNaN}), ErrorCode::InvalidArgument));
    // Infinite eye and target compare equal, but that is a non-finite input, not a coincident pair.
    EXPECT_TRUE(fails(poseLookAt({kInf, 0, 0}, {kInf, 0, 0}, kZ), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromGaze(kZero, {0, kInf, 0}, kZ), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromPrpVpnVup({0, kNaN, 0}, kZ, kY), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromYawPitchRoll(kZero, kNaN, 0, 0), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromYawPitchRoll(kZero, 0, kInf, 0), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromYawPitchRoll({kInf, 0, 0}, 0, 0, 0), ErrorCode::InvalidArgument));
    EXPECT_TRUE(
        fails(poseFromOrientation({0, 0, kNaN}, glm::dquat(1, 0, 0, 0), CameraAxes::Body), ErrorCode::InvalidArgument));
    EXPECT_TRUE(
        fails(poseFromOrientation(kZero, glm::dquat(kNaN, 0, 0, 0), CameraAxes::Body), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromRodrigues({0, kNaN, 0}, kZero), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromRodrigues(kZero, {0, 0, kInf}), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(poseFromRt(glm::dmat3(1.0), {kNaN, 0, 0}), ErrorCode::InvalidArgument));
    glm::dmat3 nanRotation(1.0);
    nanRotation[1][2] = kNaN;
    EXPECT_TRUE(fails(poseFromRt(nanRotation, kZero), ErrorCode::InvalidArgument));
}

TEST(BadInput, NonOrthonormalRotationsAndReflections)
{
    EXPECT_TRUE(fails(poseFromRt(2.0 * glm::dmat3(1.0), kZero), ErrorCode::NotOrthonormal));
    glm::dmat3 sheared(1.0);
    sheared[1][0] = 0.01;
    EXPECT_TRUE(fails(poseFromRt(sheared, kZero), ErrorCode::NotOrthonormal));
    EXPECT_TRUE(fails(poseFromRt(glm::dmat3(0.0), kZero), ErrorCode::NotOrthonormal));
    // Orthonormal but determinant -1: a mirror, which no camera pose is.
    glm::dmat3 mirror(1.0);
    mirror[2][2] = -1.0;
    EXPECT_TRUE(fails(poseFromRt(mirror, kZero), ErrorCode::NotOrthonormal));
    EXPECT_TRUE(fails(poseFromRt(-rotationFromRodrigues({0.3, -0.2, 1.0}), kZero), ErrorCode::NotOrthonormal));
    // Rounding-level deviations of a real rotation are accepted.
    glm::dmat3 rounded = rotationFromRodrigues({0.3, -0.2, 1.0});
    rounded[0][0] += 1e-12;
    EXPECT_TRUE(poseFromRt(rounded, kZero).ok());
}

TEST(BadInput, NonUnitQuaternion)
{
    EXPECT_TRUE(
        fails(poseFromOrientation(kZero, glm::dquat(2, 0, 0, 0), CameraAxes::Optical), ErrorCode::NotOrthonormal));
    EXPECT_TRUE(
        fails(poseFromOrientation(kZero, glm::dquat(0, 0, 0, 0), CameraAxes::OpenGl), ErrorCode::NotOrthonormal));
    EXPECT_TRUE(
        fails(poseFromOrientation(kZero, glm::dquat(0.5, 0.5, 0.5, 0.4), CameraAxes::Body), ErrorCode::NotOrthonormal));
}

TEST(BadInput, ExtremeButValidPoseInputsGiveFiniteRotations)
{
    // Huge and tiny vectors are still directions: |v| must not overflow to inf or underflow to 0.
    for (double scale : {1e-200, 1e-160, 1.0, 1e160, 1e200}) {
        auto gaze = poseFromGaze(kZero, scale * glm::dvec3(1, 2, -3), scale * kZ);
        ASSERT_TRUE(gaze.ok()) << "scale " << scale << ": " << gaze.error().message;
        auto reference = poseFromGaze(kZero, {1, 2, -3}, kZ);
        ASSERT_TRUE(reference.ok());
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                EXPECT_NEAR(gaze->rotation[c][r], reference->rotation[c][r], 1e-15) << "scale " << scale;
        auto prp = poseFromPrpVpnVup(kZero, scale * glm::dvec3(1, 2, -3), scale * kZ);
        ASSERT_TRUE(prp.ok()) << "scale " << scale << ": " << prp.error().message;
        EXPECT_TRUE(finite(prp->viewMatrix()));
    }
    // Nearly, but not numerically, parallel up still gives a proper frame.
    auto steep = poseLookAt(kZero, {1e-6, 0, 1}, kZ);
    ASSERT_TRUE(steep.ok());
    EXPECT_TRUE(finite(steep->viewMatrix()));
    EXPECT_NEAR(glm::determinant(steep->rotation), 1.0, 1e-12);
}

// --- Projections --------------------------------------------------------------------------------------------------

TEST(BadInput, PerspectiveRanges)
{
    const auto perspective = [](double fov, double aspect, double near, double far) {
        return Projection::perspective(FovAxis::Vertical, fov, aspect, near, far, DepthRange::MinusOneToOne);
    };
    EXPECT_TRUE(perspective(60, 1.5, 0.1, 100).ok());
    EXPECT_TRUE(perspective(60, 1.5, 0.1, kInfiniteFar).ok());
    for (double near : {0.0, -0.1, kNaN, kInf})
        EXPECT_TRUE(fails(perspective(60, 1.5, near, 100), ErrorCode::InvalidArgument)) << "near " << near;
    for (double far : {0.1, 0.05, -1.0, kNaN})
        EXPECT_TRUE(fails(perspective(60, 1.5, 0.1, far), ErrorCode::InvalidArgument)) << "far " << far;
    for (double fov : {0.0, -10.0, 180.0, 200.0, kNaN, kInf})
        EXPECT_TRUE(fails(perspective(fov, 1.5, 0.1, 100), ErrorCode::InvalidArgument)) << "fov " << fov;
    for (double aspect : {0.0, -1.5, kNaN, kInf})
        EXPECT_TRUE(fails(perspective(60, aspect, 0.1, 100), ErrorCode::InvalidArgument)) << "aspect " << aspect;
    EXPECT_TRUE(fails(Projection::perspective(FovAxis::Horizontal, 180.0, 1.5, 0.1, 100, DepthRange::ZeroToOne),
                      ErrorCode::InvalidArgument));
}

TEST(BadInput, FrustumAndOrthographicBounds)
{
    const DepthRange depth = DepthRange::ZeroToOne;
    EXPECT_TRUE(fails(Projection::frustum({1, -1, -1, 1, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({-1, -1, -1, 1, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({-1, 1, 1, -1, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({-1, 1, -1, 1, 0.0, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({-1, 1, -1, 1, 10, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({kNaN, 1, -1, 1, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::frustum({-1, 1, -kInf, 1, 0.1, 10}, depth), ErrorCode::InvalidArgument));

    EXPECT_TRUE(Projection::orthographic({-1, 1, -1, 1, -5, 10}, depth).ok()); // a box may start behind the eye
    EXPECT_TRUE(fails(Projection::orthographic({-1, 1, -1, 1, 10, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::orthographic({-1, 1, -1, 1, 10, 5}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::orthographic({2, 1, -1, 1, 0, 5}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::orthographic({-1, 1, -1, 1, 0, kInfiniteFar}, depth), ErrorCode::InvalidArgument));

    EXPECT_TRUE(fails(Projection::windowOrthographic(0, 1, 0.1, 10, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::windowOrthographic(1, 1, 10, 0.1, depth), ErrorCode::InvalidArgument));
}

TEST(BadInput, WindowIntrinsics)
{
    const DepthRange depth = DepthRange::MinusOneToOne;
    EXPECT_TRUE(Projection::window({1.0, {0.1, 0}, 0.5, 0.4, 0.1, 10}, depth).ok());
    EXPECT_TRUE(fails(Projection::window({0.0, {0, 0}, 0.5, 0.4, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({-1.0, {0, 0}, 0.5, 0.4, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({1.0, {0, 0}, 0.0, 0.4, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({1.0, {0, 0}, 0.5, -0.4, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({1.0, {kNaN, 0}, 0.5, 0.4, 0.1, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({1.0, {0, 0}, 0.5, 0.4, 0.0, 10}, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::window({1.0, {0, 0}, 0.5, 0.4, 0.1, 0.1}, depth), ErrorCode::InvalidArgument));
    // S_far scales by 1 / far: an infinite far plane has no window form (frustum() takes it).
    EXPECT_TRUE(
        fails(Projection::window({1.0, {0, 0}, 0.5, 0.4, 0.1, kInfiniteFar}, depth), ErrorCode::InvalidArgument));
}

TEST(BadInput, PinholeIntrinsics)
{
    const PinholeIntrinsics good{500, 500, 319.5, 239.5, 0, 640, 480};
    const DepthRange depth = DepthRange::ZeroToOne;
    EXPECT_TRUE(Projection::pinhole(good, 0.1, 100, depth).ok());
    for (double f : {0.0, -500.0, kNaN}) {
        PinholeIntrinsics k = good;
        k.fx = f;
        EXPECT_TRUE(fails(Projection::pinhole(k, 0.1, 100, depth), ErrorCode::InvalidArgument)) << "fx " << f;
        k = good;
        k.fy = f;
        EXPECT_TRUE(fails(Projection::pinhole(k, 0.1, 100, depth), ErrorCode::InvalidArgument)) << "fy " << f;
    }
    for (auto [w, h] : {std::pair{0, 480}, std::pair{640, 0}, std::pair{-640, 480}}) {
        PinholeIntrinsics k = good;
        k.width = w;
        k.height = h;
        EXPECT_TRUE(fails(Projection::pinhole(k, 0.1, 100, depth), ErrorCode::InvalidArgument)) << w << "x" << h;
    }
    PinholeIntrinsics k = good;
    k.cy = kInf;
    EXPECT_TRUE(fails(Projection::pinhole(k, 0.1, 100, depth), ErrorCode::InvalidArgument));
    k = good;
    k.skew = kNaN;
    EXPECT_TRUE(fails(Projection::pinhole(k, 0.1, 100, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::pinhole(good, -0.1, 100, depth), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Projection::pinhole(good, 1.0, 0.5, depth), ErrorCode::InvalidArgument));
}

// --- Viewports ----------------------------------------------------------------------------------------------------

TEST(BadInput, Viewports)
{
    EXPECT_TRUE(fails(Viewport::create({0, 480}), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, -1}), ErrorCode::InvalidArgument));
    // Empty windows.
    EXPECT_TRUE(fails(Viewport::create({640, 480, PixelRect{0, 0, 0, 100}}), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, 480, PixelRect{0, 0, 100, -5}}), ErrorCode::InvalidArgument));
    // Windows that do not fit the frame.
    EXPECT_TRUE(fails(Viewport::create({640, 480, PixelRect{600, 0, 100, 100}}), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, 480, PixelRect{-1, 0, 100, 100}}), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, 480, PixelRect{0, 400, 100, 81}, Origin::BottomLeft}),
                      ErrorCode::InvalidArgument));
    EXPECT_TRUE(Viewport::create({640, 480, PixelRect{0, 400, 100, 80}, Origin::BottomLeft}).ok());
    // Bad scissors: outside the frame or of negative size.
    EXPECT_TRUE(fails(Viewport::create({640, 480, std::nullopt, Origin::TopLeft, 1.0, PixelRect{630, 0, 20, 20}}),
                      ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, 480, std::nullopt, Origin::TopLeft, 1.0, PixelRect{10, 10, -5, 20}}),
                      ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Viewport::create({640, 480, std::nullopt, Origin::TopLeft, 1.0, PixelRect{0, -1, 5, 20}}),
                      ErrorCode::InvalidArgument));
    // Pixel aspect.
    for (double aspect : {0.0, -1.0, kNaN, kInf})
        EXPECT_TRUE(
            fails(Viewport::create({640, 480, std::nullopt, Origin::TopLeft, aspect}), ErrorCode::InvalidArgument))
            << "pixel aspect " << aspect;
}

// --- Cameras and lenses -------------------------------------------------------------------------------------------

class BadInputCamera : public ::testing::Test
{
protected:
    Viewport viewport_ = *Viewport::create({640, 480});
    Projection pinhole_ =
        *Projection::pinhole({500, 500, 319.5, 239.5, 0, 640, 480}, 0.1, 100, DepthRange::MinusOneToOne);
};

TEST_F(BadInputCamera, DistortionWithoutPinholeIntrinsicsIsUnsupported)
{
    Distortion distortion{DistortionModel::RadialTangential, {-0.1, 0.01, 0, 0, 0}};
    auto fov = Projection::perspective(FovAxis::Vertical, 60, 4.0 / 3.0, 0.1, 100, DepthRange::MinusOneToOne);
    auto frustum = Projection::frustum({-1, 1, -0.75, 0.75, 1, 100}, DepthRange::ZeroToOne);
    auto window = Projection::window({1, {0, 0}, 0.5, 0.375, 0.1, 100}, DepthRange::ZeroToOne);
    ASSERT_TRUE(fov.ok() && frustum.ok() && window.ok());
    EXPECT_TRUE(fails(Camera::create(Pose{}, *fov, distortion, viewport_), ErrorCode::Unsupported));
    EXPECT_TRUE(fails(Camera::create(Pose{}, *frustum, distortion, viewport_), ErrorCode::Unsupported));
    EXPECT_TRUE(fails(Camera::create(Pose{}, *window, Distortion{DistortionModel::Fisheye, {0.1}}, viewport_),
                      ErrorCode::Unsupported));
    // The same distortion on pinhole intrinsics is fine, and no distortion is fine on any form.
    EXPECT_TRUE(Camera::create(Pose{}, pinhole_, distortion, viewport_).ok());
    EXPECT_TRUE(Camera::create(Pose{}, *fov, Distortion{}, viewport_).ok());
}

TEST_F(BadInputCamera, ExtraNonZeroDistortionCoefficients)
{
    // Five coefficients for plumb_bob, four for fisheye: anything set beyond them is a mistake, not ignored.
    Distortion radial{DistortionModel::RadialTangential, {-0.1, 0.01, 0, 0, 0, 0.2}};
    EXPECT_TRUE(fails(Camera::create(Pose{}, pinhole_, radial, viewport_), ErrorCode::InvalidArgument));
    Distortion fisheye{DistortionModel::Fisheye, {0.1, 0, 0, 0, 0.05}};
    EXPECT_TRUE(fails(Camera::create(Pose{}, pinhole_, fisheye, viewport_), ErrorCode::InvalidArgument));
    Distortion rational{DistortionModel::Rational, {-0.1, 0.01, 0, 0, 0, 0.1, 0, kNaN}};
    EXPECT_TRUE(fails(Camera::create(Pose{}, pinhole_, rational, viewport_), ErrorCode::InvalidArgument));
    Distortion none{DistortionModel::None, {0.1}};
    EXPECT_FALSE(validateDistortion(none).ok());
    EXPECT_TRUE(fails(Camera::create(Pose{}, pinhole_, none, viewport_), ErrorCode::InvalidArgument));
}

TEST_F(BadInputCamera, BadViewMatrices)
{
    glm::dmat4 nanView(1.0);
    nanView[3][1] = kNaN;
    EXPECT_TRUE(fails(Camera::create(nanView, pinhole_, Distortion{}, viewport_), ErrorCode::InvalidArgument));
    EXPECT_TRUE(fails(Camera::create(glm::dmat4(0.0), pinhole_, Distortion{}, viewport_), ErrorCode::DegenerateBasis));
}

} // namespace
