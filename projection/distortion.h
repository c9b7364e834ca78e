// SPDX-License-Identifier: Apache-2.0
// Lens distortion models of OpenCV (and ROS camera_info), applied to normalized optical coordinates.
#pragma once

#include <array>

#include <glm/vec2.hpp>

#include "base/result.h"

namespace overlayd {

enum class DistortionModel {
    None,
    RadialTangential, // OpenCV 5 coefficients / ROS "plumb_bob": k1, k2, p1, p2, k3
    Rational,         // OpenCV 8 coefficients / ROS "rational_polynomial": k1, k2, p1, p2, k3, k4, k5, k6
    Fisheye,          // OpenCV fisheye / ROS "equidistant": k1, k2, k3, k4 on theta = atan(r)
};

// A fisheye's declared field of view is below a full turn.
inline constexpr double kMaxFisheyeFieldDeg = 360.0;

struct Distortion {
    DistortionModel model = DistortionModel::None;
    std::array<double, 8> coeffs{}; // in the order listed beside each model; unused trailing entries are 0
    // Fisheye only: the lens's full field of view in degrees as the configuration declares it, 0 when it does not.
    // OpenCV's and ROS's fisheye calibrations describe the front hemisphere only, and their polynomials usually
    // keep growing past 90 degrees, so the field goes behind the camera plane only when declared beyond 180.
    double fieldDeg = 0.0;

    bool operator==(const Distortion &) const = default;
};

// How many coefficients a model takes (0, 5, 8, 4).
int coefficientCount(DistortionModel model);
Status validateDistortion(const Distortion &distortion);

// (x, y) = (X/Z, Y/Z) in the optical frame -> the distorted normalized point, exactly as OpenCV computes it.
glm::dvec2 distortNormalized(const Distortion &distortion, const glm::dvec2 &xy);
// Inverse of distortNormalized by Newton's method, to 1e-12; fails rather than return a wrong point.
Result<glm::dvec2> undistortNormalized(const Distortion &distortion, const glm::dvec2 &distorted);
// The radius |(x, y)| up to which the radial mapping keeps increasing. Past it, polynomial models fold back and
// send points far outside the calibrated field onto the image, so nothing beyond it is drawn.
// For a fisheye that is +infinity when its field goes past 90 degrees from the axis (fisheyeFieldAngle).
double monotonicRadius(const Distortion &distortion);
// The fisheye's angle from the optical axis up to which theta_d keeps growing, scanned in steps of 0.01 degrees
// up to 179.99 degrees: a lens of more than 180 degrees field of view sees points behind the camera plane.
double fisheyeMaxAngle(const Distortion &distortion);
// The fisheye's valid angle from the axis: the front hemisphere (the model scanned up to 89 degrees, as for the
// other models) unless fieldDeg declares more than 180 degrees; then fisheyeMaxAngle; either capped at half of a
// declared fieldDeg.
double fisheyeFieldAngle(const Distortion &distortion);
// The angle theta in [0, maxAngle] whose distorted angle theta_d(theta) is thetaD (the fisheye model's inverse
// on the angle, which unlike X/Z goes on past 90 degrees); fails beyond theta_d(maxAngle).
Result<double> undistortFisheyeAngle(const Distortion &distortion, double thetaD, double maxAngle);

} // namespace overlayd
