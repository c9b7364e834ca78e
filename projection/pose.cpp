// SPDX-License-Identifier: Apache-2.0
// Camera pose builders: the viewing pipeline's graphics forms, orientations, and OpenCV/ROS extrinsics.
#include "pose.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_access.hpp>

#include "checks.h"

namespace overlayd {

glm::dmat4 Pose::viewMatrix() const
{
    glm::dmat4 view(rotation);
    view[3] = glm::dvec4(translation, 1.0);
    return view;
}

glm::dvec3 Pose::position() const
{
    return -(glm::transpose(rotation) * translation);
}

glm::dmat3 internalFromAxes(CameraAxes axes)
{
    // GLM matrices are column-major: each dvec3 below is a column, i.e. where that input axis lands.
    switch (axes) {
    case CameraAxes::Body: // x forward -> -Z, y left -> -X, z up -> +Y
        return glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0));
    case CameraAxes::Optical: // x right -> X, y down -> -Y, z forward -> -Z
        return glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1));
    case CameraAxes::OpenGl:
        break;
    }
    return glm::dmat3(1.0);
}

namespace {

// v / |v| without overflow or underflow: |v| of a finite vector past 1e154 (or below 1e-154) would square to inf
// (or 0) and turn a usable direction into a refused one. Nothing for the zero vector.
std::optional<glm::dvec3> unitDirection(const glm::dvec3 &v)
{
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (largest == 0.0)
        return std::nullopt;
    return glm::normalize(v / largest);
}

// Builds the pose whose camera axes, expressed in world coordinates, are the columns u, v, w.
Pose poseFromBasis(const glm::dvec3 &eye, const glm::dvec3 &u, const glm::dvec3 &v, const glm::dvec3 &w)
{
    Pose pose;
    pose.rotation = glm::transpose(glm::dmat3(u, v, w));
    pose.translation = -(pose.rotation * eye);
    return pose;
}

} // namespace

Result<Pose> poseFromGaze(const glm::dvec3 &eye, const glm::dvec3 &gaze, const glm::dvec3 &up)
{
    if (!Checks::finite(eye) || !Checks::finite(gaze) || !Checks::finite(up))
        return makeError(ErrorCode::InvalidArgument, "eye, gaze and up must be finite");
    const auto gazeDirection = unitDirection(gaze);
    const auto upDirection = unitDirection(up);
    if (!gazeDirection)
        return makeError(ErrorCode::DegenerateBasis, "gaze direction is the zero vector");
    if (!upDirection)
        return makeError(ErrorCode::DegenerateBasis, "up vector is the zero vector");
    const glm::dvec3 w = -*gazeDirection;
    const glm::dvec3 side = glm::cross(*upDirection, w);
    if (glm::length(side) <= Checks::kDegenerate)
        return makeError(ErrorCode::DegenerateBasis,
                         "up " + Checks::str(up) + " is parallel to the gaze direction " + Checks::str(gaze));
    const glm::dvec3 u = glm::normalize(side);
    const glm::dvec3 v = glm::cross(w, u);
    return poseFromBasis(eye, u, v, w);
}

Result<Pose> poseLookAt(const glm::dvec3 &eye, const glm::dvec3 &target, const glm::dvec3 &up)
{
    // Non-finite first: infinite eye and target compare equal but are not "the same point".
    if (!Checks::finite(eye) || !Checks::finite(target) || !Checks::finite(up))
        return makeError(ErrorCode::InvalidArgument, "eye, target and up must be finite");
    if (eye == target)
        return makeError(ErrorCode::DegenerateBasis, "eye and target are the same point " + Checks::str(eye));
    return poseFromGaze(eye, target - eye, up);
}

Result<Pose> poseFromPrpVpnVup(const glm::dvec3 &prp, const glm::dvec3 &vpn, const glm::dvec3 &vup)
{
    if (!Checks::finite(prp) || !Checks::finite(vpn) || !Checks::finite(vup))
        return makeError(ErrorCode::InvalidArgument, "PRP, VPN and VUP must be finite");
    const auto vpnDirection = unitDirection(vpn);
    const auto vupDirection = unitDirection(vup);
    if (!vpnDirection)
        return makeError(ErrorCode::DegenerateBasis, "VPN is the zero vector");
    if (!vupDirection)
        return makeError(ErrorCode::DegenerateBasis, "VUP is the zero vector");
    const glm::dvec3 zAxis = *vpnDirection;
    const glm::dvec3 side = glm::cross(*vupDirection, zAxis);
    if (glm::length(side) <= Checks::kDegenerate)
        return makeError(ErrorCode::DegenerateBasis,
                         "VUP " + Checks::str(vup) + " is parallel to VPN " + Checks::str(vpn));
    const glm::dvec3 xAxis = glm::normalize(side);
    const glm::dvec3 yAxis = glm::cross(zAxis, xAxis);
    return poseFromBasis(prp, xAxis, yAxis, zAxis);
}

Result<Pose> poseFromOrientation(const glm::dvec3 &position, const glm::dquat &worldFromAxes, CameraAxes axes)
{
    const double norm = std::sqrt(glm::dot(worldFromAxes, worldFromAxes));
    if (!std::isfinite(norm) || !Checks::finite(position))
        return makeError(ErrorCode::InvalidArgument, "position and orientation must be finite");
    if (std::abs(norm - 1.0) > Checks::kOrthonormal)
        return makeError(ErrorCode::NotOrthonormal,
                         "orientation quaternion is not of unit length (|q| = " + Checks::str(norm) + ")");
    const glm::dmat3 worldFromGivenAxes = glm::mat3_cast(worldFromAxes / norm);
    const glm::dmat3 worldFromInternal = worldFromGivenAxes * glm::transpose(internalFromAxes(axes));
    return poseFromBasis(position, worldFromInternal[0], worldFromInternal[1], worldFromInternal[2]);
}

Result<Pose> poseFromYawPitchRoll(const glm::dvec3 &position, double yawDeg, double pitchDeg, double rollDeg)
{
    if (!std::isfinite(yawDeg) || !std::isfinite(pitchDeg) || !std::isfinite(rollDeg))
        return makeError(ErrorCode::InvalidArgument, "yaw, pitch and roll must be finite");
    const glm::dquat yaw = glm::angleAxis(glm::radians(yawDeg), glm::dvec3(0, 0, 1));
    const glm::dquat pitch = glm::angleAxis(glm::radians(pitchDeg), glm::dvec3(0, 1, 0));
    const glm::dquat roll = glm::angleAxis(glm::radians(rollDeg), glm::dvec3(1, 0, 0));
    return poseFromOrientation(position, yaw * pitch * roll, CameraAxes::Body);
}

YawPitchRoll yawPitchRollOf(const Pose &pose)
{
    // world_from_body = Rz(yaw) Ry(pitch) Rx(roll); its first column is the optical axis.
    const glm::dmat3 worldFromBody = glm::transpose(pose.rotation) * internalFromAxes(CameraAxes::Body);
    const glm::dvec3 forward = worldFromBody[0];
    const double cosPitch = std::hypot(forward.x, forward.y);
    YawPitchRoll out;
    out.position = pose.position();
    // atan2, not asin: asin loses half the digits near +-90 degrees, where its slope is infinite.
    out.pitchDeg = glm::degrees(std::atan2(-forward.z, cosPitch));
    // Straight up or down, to rounding, only yaw - roll (or yaw + roll) is defined: all of it goes in yaw. The roll
    // left out moves the rotation by cos(pitch) * roll, under 1e-14 rad: no further from the lock than this.
    if (cosPitch < 4.0 * std::numeric_limits<double>::epsilon()) {
        out.yawDeg = glm::degrees(std::atan2(-worldFromBody[1][0], worldFromBody[1][1]));
        out.rollDeg = 0.0;
        return out;
    }
    // Near the lock, yaw from the optical axis alone has an error of about eps / cos(pitch); roll is read from what
    // yaw and pitch leave, Rx(roll) = Ry(pitch)^T Rz(yaw)^T world_from_body, so that it takes that error back and
    // the three angles rebuild the rotation to rounding at every pitch.
    const double yaw = std::atan2(forward.y, forward.x), pitch = glm::radians(out.pitchDeg);
    const glm::dmat3 rollOnly = glm::transpose(glm::mat3_cast(glm::angleAxis(yaw, glm::dvec3(0, 0, 1)) *
                                                              glm::angleAxis(pitch, glm::dvec3(0, 1, 0)))) *
                                worldFromBody;
    out.yawDeg = glm::degrees(yaw);
    out.rollDeg = glm::degrees(std::atan2(rollOnly[1][2] - rollOnly[2][1], rollOnly[1][1] + rollOnly[2][2]));
    return out;
}

Result<Pose> poseFromRt(const glm::dmat3 &rotation, const glm::dvec3 &translation)
{
    if (auto status = Checks::requireRotation(rotation, "extrinsic rotation R"); !status)
        return status.error();
    if (!Checks::finite(translation))
        return makeError(ErrorCode::InvalidArgument, "extrinsic translation t must be finite");
    // x_internal = F x_optical with F = diag(1, -1, -1): exact, no rounding is introduced.
    const glm::dmat3 flip = internalFromAxes(CameraAxes::Optical);
    return Pose{flip * rotation, flip * translation};
}

glm::dmat3 rotationFromRodrigues(const glm::dvec3 &rvec)
{
    const double theta = glm::length(rvec);
    if (theta < 1e-300)
        return glm::dmat3(1.0);
    const glm::dvec3 k = rvec / theta;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    // Column-major cross-product matrix [k]x.
    const glm::dmat3 cross(glm::dvec3(0, k.z, -k.y), glm::dvec3(-k.z, 0, k.x), glm::dvec3(k.y, -k.x, 0));
    return c * glm::dmat3(1.0) + (1.0 - c) * glm::outerProduct(k, k) + s * cross;
}

Result<Pose> poseFromRodrigues(const glm::dvec3 &rvec, const glm::dvec3 &tvec)
{
    if (!Checks::finite(rvec))
        return makeError(ErrorCode::InvalidArgument, "rvec must be finite");
    return poseFromRt(rotationFromRodrigues(rvec), tvec);
}

} // namespace overlayd
