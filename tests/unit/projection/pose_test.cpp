// SPDX-License-Identifier: Apache-2.0
// pose_test: each pose form puts the camera where hand-checked cases say, looking and pointing up as expected.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "projection/pose.h"

using namespace overlayd;

namespace {

constexpr double kTolerance = 1e-12;

// The camera's axes in world coordinates: the internal frame looks down -Z with Y up and X right.
glm::dvec3 forwardOf(const Pose &pose)
{
    return glm::transpose(pose.rotation) * glm::dvec3(0, 0, -1);
}
glm::dvec3 upOf(const Pose &pose)
{
    return glm::transpose(pose.rotation) * glm::dvec3(0, 1, 0);
}
glm::dvec3 rightOf(const Pose &pose)
{
    return glm::transpose(pose.rotation) * glm::dvec3(1, 0, 0);
}

void expectVec(const glm::dvec3 &actual, const glm::dvec3 &expected, const char *what)
{
    EXPECT_NEAR(actual.x, expected.x, kTolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, kTolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, kTolerance) << what;
}

void expectCamera(const Result<Pose> &pose, const glm::dvec3 &position, const glm::dvec3 &forward, const glm::dvec3 &up,
                  const glm::dvec3 &right)
{
    ASSERT_TRUE(pose.ok()) << pose.error().message;
    expectVec(pose->position(), position, "position");
    expectVec(forwardOf(*pose), forward, "forward");
    expectVec(upOf(*pose), up, "up");
    expectVec(rightOf(*pose), right, "right");
    // The camera centre maps to the origin of the camera frame.
    expectVec(pose->rotation * position + pose->translation, {0, 0, 0}, "centre in camera frame");
}

void expectRotation(const glm::dmat3 &r)
{
    const glm::dmat3 gram = glm::transpose(r) * r;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            EXPECT_NEAR(gram[c][row], c == row ? 1.0 : 0.0, 1e-12);
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12);
}

const glm::dvec3 kX{1, 0, 0}, kY{0, 1, 0}, kZ{0, 0, 1};
const glm::dvec3 kEye{1.0, 2.0, 3.0};

TEST(Pose, LookAtAlongWorldY)
{
    expectCamera(poseLookAt(kEye, kEye + 5.0 * kY, kZ), kEye, kY, kZ, kX);
    // The target lands on the camera's -Z axis at its distance.
    auto pose = poseLookAt(kEye, kEye + 5.0 * kY, kZ);
    ASSERT_TRUE(pose.ok());
    expectVec(glm::dvec3(pose->viewMatrix() * glm::dvec4(kEye + 5.0 * kY, 1.0)), {0, 0, -5}, "target");
}

TEST(Pose, LookAtWithTiltedUpKeepsUpInTheGazePlane)
{
    // Up need not be perpendicular to the gaze: the camera's up is its component perpendicular to the gaze.
    expectCamera(poseLookAt({0, 0, 0}, {0, 0, -4}, {0, 1, 1}), {0, 0, 0}, {0, 0, -1}, kY, kX);
    // Looking straight down with north (+Y) up: right is east (+X).
    expectCamera(poseLookAt({0, 0, 10}, {0, 0, 0}, kY), {0, 0, 10}, -kZ, kY, kX);
}

TEST(Pose, GazeAlongMinusX)
{
    expectCamera(poseFromGaze(kEye, {-3, 0, 0}, kZ), kEye, -kX, kZ, kY);
}

TEST(Pose, PrpVpnVupWithVpnPointingBackTowardsTheViewer)
{
    // The viewing pipeline: VPN points from the window back to the viewer, so the camera looks along -VPN.
    expectCamera(poseFromPrpVpnVup(kEye, {0, -2, 0}, kZ), kEye, kY, kZ, kX);
    expectCamera(poseFromPrpVpnVup(kEye, kZ, kY), kEye, -kZ, kY, kX);
}

TEST(Pose, YawPitchRollHandChecked)
{
    // Body axes x forward, y left, z up (REP 103); zero angles look along world +X with -Y to the right.
    expectCamera(poseFromYawPitchRoll(kEye, 0, 0, 0), kEye, kX, kZ, -kY);
    // Yaw 90 (counter-clockwise seen from above) looks along world +Y.
    expectCamera(poseFromYawPitchRoll(kEye, 90, 0, 0), kEye, kY, kZ, kX);
    expectCamera(poseFromYawPitchRoll(kEye, 180, 0, 0), kEye, -kX, kZ, kY);
    // Positive pitch looks down.
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    expectCamera(poseFromYawPitchRoll(kEye, 0, 30, 0), kEye, {c, 0, -s}, {s, 0, c}, -kY);
    // Positive roll about the forward axis turns the left side up: the camera's right points down.
    expectCamera(poseFromYawPitchRoll(kEye, 0, 0, 90), kEye, kX, -kY, -kZ);
    // Yaw then pitch: yaw 90, pitch 45 looks along +Y and down.
    const double h = std::sqrt(0.5);
    expectCamera(poseFromYawPitchRoll(kEye, 90, 45, 0), kEye, {0, h, -h}, {0, h, h}, kX);
}

TEST(Pose, YawPitchRollEqualsTheAerospaceRotationWrittenOut)
{
    // world_from_body = Rz(yaw) Ry(pitch) Rx(roll) written out element by element.
    const auto rz = [](double a) {
        return glm::dmat3(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
    };
    const auto ry = [](double a) {
        return glm::dmat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a));
    };
    const auto rx = [](double a) {
        return glm::dmat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a));
    };
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> angle(-180.0, 180.0), pitch(-89.0, 89.0);
    for (int i = 0; i < 100; ++i) {
        const double y = angle(rng), p = pitch(rng), r = angle(rng);
        const glm::dmat3 body = rz(glm::radians(y)) * ry(glm::radians(p)) * rx(glm::radians(r));
        // Body x is forward, z is up, -y is right.
        expectCamera(poseFromYawPitchRoll(kEye, y, p, r), kEye, body[0], body[2], -body[1]);
    }
}

TEST(Pose, OrientationIdentityForEachAxesConvention)
{
    const glm::dquat identity(1, 0, 0, 0);
    // Body: x forward, y left, z up.
    expectCamera(poseFromOrientation(kEye, identity, CameraAxes::Body), kEye, kX, kZ, -kY);
    // Optical: x right, y down, z forward.
    expectCamera(poseFromOrientation(kEye, identity, CameraAxes::Optical), kEye, kZ, -kY, kX);
    // OpenGL: x right, y up, looking down -z.
    expectCamera(poseFromOrientation(kEye, identity, CameraAxes::OpenGl), kEye, -kZ, kY, kX);
    // A quarter turn about world Z turns each of them left.
    const glm::dquat quarter = glm::angleAxis(M_PI / 2, kZ);
    expectCamera(poseFromOrientation(kEye, quarter, CameraAxes::Body), kEye, kY, kZ, kX);
    expectCamera(poseFromOrientation(kEye, quarter, CameraAxes::Optical), kEye, kZ, kX, kY);
}

TEST(Pose, InternalFromAxesMapsEachConventionsAxes)
{
    expectVec(internalFromAxes(CameraAxes::Body) * kX, {0, 0, -1}, "body forward");
    expectVec(internalFromAxes(CameraAxes::Body) * kY, {-1, 0, 0}, "body left");
    expectVec(internalFromAxes(CameraAxes::Body) * kZ, {0, 1, 0}, "body up");
    expectVec(internalFromAxes(CameraAxes::Optical) * kY, {0, -1, 0}, "optical down");
    expectVec(internalFromAxes(CameraAxes::Optical) * kZ, {0, 0, -1}, "optical forward");
    for (CameraAxes axes : {CameraAxes::Body, CameraAxes::Optical, CameraAxes::OpenGl})
        expectRotation(internalFromAxes(axes));
}

TEST(Pose, RtIdentityLooksAlongWorldZWithYDown)
{
    // x_optical = R x_world + t: with R = I the camera sits at -t and looks along world +Z, image rows along +Y.
    expectCamera(poseFromRt(glm::dmat3(1.0), {0, 0, 5}), {0, 0, -5}, kZ, -kY, kX);
    expectCamera(poseFromRt(glm::dmat3(1.0), {1, -2, 0}), {-1, 2, 0}, kZ, -kY, kX);
}

TEST(Pose, RodriguesQuarterTurnAboutZ)
{
    // R = Rz(90): the optical axes in world are the rows of R: right = (0, -1, 0), down = (1, 0, 0), forward = Z.
    const glm::dvec3 t{0.5, 0.0, 2.0};
    const glm::dvec3 position = -(glm::transpose(glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 1)) * t);
    expectCamera(poseFromRodrigues({0, 0, M_PI / 2}, t), position, kZ, -kX, -kY);
    // A zero rvec is the identity.
    expectCamera(poseFromRodrigues({0, 0, 0}, {0, 0, 5}), {0, 0, -5}, kZ, -kY, kX);
}

TEST(Pose, EveryFormGivesAProperRotation)
{
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    const auto vec = [&] {
        return glm::dvec3(u(rng), u(rng), u(rng));
    };
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 eye = vec(), a = vec(), b = vec();
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 1e-3)
            continue;
        for (const Result<Pose> &pose :
             {poseLookAt(eye, eye + a, b), poseFromGaze(eye, a, b), poseFromPrpVpnVup(eye, a, b),
              poseFromYawPitchRoll(eye, 18 * u(rng), 9 * u(rng), 18 * u(rng)),
              poseFromOrientation(eye, glm::normalize(glm::dquat(u(rng), u(rng), u(rng), u(rng))), CameraAxes::Body),
              poseFromRodrigues(a / 3.0, b)}) {
            ASSERT_TRUE(pose.ok()) << pose.error().message;
            expectRotation(pose->rotation);
        }
        auto pose = poseLookAt(eye, eye + a, b);
        ASSERT_TRUE(pose.ok());
        expectVec(forwardOf(*pose), glm::normalize(a), "lookAt forward");
        // Up lies in the plane of the given up and the gaze, on the up side.
        EXPECT_NEAR(glm::dot(upOf(*pose), glm::cross(a, b)), 0.0, 1e-9);
        EXPECT_GT(glm::dot(upOf(*pose), b), 0.0);
    }
}

} // namespace

// yawPitchRollOf against the forward form, on random poses and at gimbal lock: the angles it gives rebuild the same
// rotation (compared as matrices, the one meaning angles share), and away from lock they are the angles given.
TEST(YawPitchRollOf, RebuildsTheRotationAndRecoversTheAngles)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> yaw(-179.0, 179.0), pitch(-89.0, 89.0), roll(-179.0, 179.0),
        metres(-10.0, 10.0);
    for (int i = 0; i < 500; ++i) {
        const glm::dvec3 position(metres(random), metres(random), metres(random));
        const double y = yaw(random), p = pitch(random), r = roll(random);
        const Pose pose = *poseFromYawPitchRoll(position, y, p, r);
        const YawPitchRoll back = yawPitchRollOf(pose);
        EXPECT_NEAR(back.yawDeg, y, 1e-9);
        EXPECT_NEAR(back.pitchDeg, p, 1e-9);
        EXPECT_NEAR(back.rollDeg, r, 1e-9);
        EXPECT_LT(glm::length(back.position - position), 1e-9);
    }
    for (const double p : {90.0, -90.0}) {
        const Pose pose = *poseFromYawPitchRoll({1, 2, 3}, 30.0, p, 20.0);
        const YawPitchRoll back = yawPitchRollOf(pose);
        EXPECT_NEAR(back.pitchDeg, p, 1e-6);
        EXPECT_EQ(back.rollDeg, 0.0);
        const Pose rebuilt = *poseFromYawPitchRoll(back.position, back.yawDeg, back.pitchDeg, back.rollDeg);
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                EXPECT_NEAR(rebuilt.rotation[c][r], pose.rotation[c][r], 1e-6) << "pitch " << p;
    }
}

// Close to straight up or down, where yaw and roll nearly share one axis, the angles must still rebuild the rotation
// to rounding: a pose saved in yaw/pitch/roll must project as the live one did. (Folding the roll into yaw within
// 1.4e-6 rad of the lock moved a point 1e-3 px at 100 px of focal length.)
TEST(YawPitchRollOf, RebuildsTheRotationToRoundingNearGimbalLock)
{
    for (const double p : {89.99992, -89.99992, 90.0 - 1e-7, 90.0 - 1e-9, 90.0 - 1e-11, -90.0 + 1e-10, 89.0})
        for (const double r : {0.0, 0.7, 37.0, -120.0, 179.5}) {
            const Pose pose = *poseFromYawPitchRoll({1, 2, 3}, 30.0, p, r);
            const YawPitchRoll back = yawPitchRollOf(pose);
            const Pose rebuilt = *poseFromYawPitchRoll(back.position, back.yawDeg, back.pitchDeg, back.rollDeg);
            for (int c = 0; c < 3; ++c)
                for (int row = 0; row < 3; ++row)
                    EXPECT_NEAR(rebuilt.rotation[c][row], pose.rotation[c][row], 1e-13)
                        << "pitch " << p << ", roll " << r << ": rebuilt from yaw " << back.yawDeg << ", pitch "
                        << back.pitchDeg << ", roll " << back.rollDeg;
        }
}
