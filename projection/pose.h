// SPDX-License-Identifier: Apache-2.0
// Camera pose (extrinsics): every way users describe it, converging on one world-to-camera rigid transform.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "base/result.h"

namespace overlayd {

// The internal camera frame is OpenGL's: X right, Y up, looking down -Z.
// A Pose maps world points into it: x_camera = rotation * x_world + translation.
struct Pose {
    glm::dmat3 rotation{1.0};
    glm::dvec3 translation{0.0};

    glm::dmat4 viewMatrix() const;
    glm::dvec3 position() const; // the camera centre in world coordinates

    bool operator==(const Pose &) const = default;
};

// How the axes of a given orientation are laid out on the camera.
enum class CameraAxes {
    Body,    // x forward (optical axis), y left, z up: ROS REP 103 body frame
    Optical, // x right, y down, z forward: OpenCV and ROS "_optical_frame"
    OpenGl,  // x right, y up, looking down -z: the internal frame
};

// Rotation taking vectors in the given camera axes to the internal (OpenGL) camera axes.
glm::dmat3 internalFromAxes(CameraAxes axes);

// Eye, gaze and up: w = -g/|g|, u = t x w / |t x w|, v = w x u.
Result<Pose> poseFromGaze(const glm::dvec3 &eye, const glm::dvec3 &gaze, const glm::dvec3 &up);
// Eye, a target point looked at, and up (gluLookAt).
Result<Pose> poseLookAt(const glm::dvec3 &eye, const glm::dvec3 &target, const glm::dvec3 &up);
// PRP, VPN, VUP: Z' = VPN (pointing back towards the viewer), X' = normalize(VUP x VPN), Y' = Z' x X'.
Result<Pose> poseFromPrpVpnVup(const glm::dvec3 &prp, const glm::dvec3 &vpn, const glm::dvec3 &vup);
// Position plus the orientation of the camera's `axes` in the world (a unit quaternion, world_from_axes).
Result<Pose> poseFromOrientation(const glm::dvec3 &position, const glm::dquat &worldFromAxes, CameraAxes axes);
// Position plus yaw, pitch, roll in degrees of the Body axes, ROS/aerospace order:
// world_from_body = Rz(yaw) * Ry(pitch) * Rx(roll). With a Z-up world, positive pitch turns the optical axis down.
Result<Pose> poseFromYawPitchRoll(const glm::dvec3 &position, double yawDeg, double pitchDeg, double rollDeg);
// The inverse of poseFromYawPitchRoll: the camera's position and its Body axes' yaw, pitch (within [-90, 90]) and
// roll in degrees. At pitch +-90 (looking straight down or up) yaw and roll share one angle: roll is reported 0.
struct YawPitchRoll {
    glm::dvec3 position{0.0};
    double yawDeg = 0.0, pitchDeg = 0.0, rollDeg = 0.0;
};
YawPitchRoll yawPitchRollOf(const Pose &pose);
// OpenCV/ROS extrinsics: x_optical = R * x_world + t, camera looking along +Z with Y down.
Result<Pose> poseFromRt(const glm::dmat3 &rotation, const glm::dvec3 &translation);
// OpenCV's rvec (Rodrigues axis * angle in radians) and tvec.
Result<Pose> poseFromRodrigues(const glm::dvec3 &rvec, const glm::dvec3 &tvec);

// Rodrigues' formula: the rotation by |rvec| radians about rvec.
glm::dmat3 rotationFromRodrigues(const glm::dvec3 &rvec);

} // namespace overlayd
