// SPDX-License-Identifier: Apache-2.0
// solvePose: the camera pose from world points and the pixels they were seen at (PnP), for any lens the Camera
// models: each pixel goes back through the Camera's own exact unprojection to a normalized direction, so OpenCV's
// solver sees an ideal pinhole (K = I, no distortion) whatever the lens.
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/result.h"
#include "projection/camera.h"
#include "projection/distortion.h"
#include "projection/pose.h"

namespace overlayd {

inline constexpr size_t kMinCorrespondences = 4, kMaxCorrespondences = 10000;
inline constexpr double kLargeRmsPx = 2.0; // above this the result is reported with a warning
// A flat set of points whose plane is tilted at most this far from level has an up side (its normal with z > 0):
// a camera solved on the other side is warned about (u and v swapped mirror it there).
inline constexpr double kMaxUpPlaneTiltDeg = 60.0;
// A coplanar set seen from less than this far above its plane (the angle at its centroid) is warned about.
inline constexpr double kMinPlaneElevationDeg = 10.0;

struct Correspondence {
    glm::dvec3 world;
    glm::dvec2 pixel; // memory order (top-left origin), as the Camera counts
};

// OpenCV's solvers, each refined by solvePnPRefineLM: SQPnP (any 4+ points, globally optimal; the default), the
// iterative Levenberg-Marquardt from a DLT start (6+ points, or 4+ coplanar ones), IPPE (4+ coplanar points: a
// marked floor).
enum class PnpSolver { Sqpnp, Iterative, Ippe };

struct PoseSolution {
    Pose pose;                    // world to camera (the internal OpenGL frame)
    std::vector<double> errorsPx; // per point: distance between its pixel and its reprojection
    double rmsPx = 0.0;
    std::vector<std::string> warnings; // degenerate geometry, large error
};

// `camera` supplies intrinsics, lens and viewport (its pose only expresses the rays it unprojects, then is undone);
// `distortion` is the lens it was built with, to reproject through the solved pose. Refused: fewer than 4 or more
// than 10000 points, an orthographic camera, a pixel outside the lens's image circle or behind it, world points
// that are collinear or all one point, and a solver given points it cannot take (IPPE off a plane, the iterative
// solver with fewer than 6 points off a plane).
Result<PoseSolution> solvePose(const Camera &camera, const Distortion &distortion,
                               const std::vector<Correspondence> &points, PnpSolver solver = PnpSolver::Sqpnp);

// OpenCV's rvec/tvec (x_optical = R x + t) of a pose, as the config's `rvec`/`tvec` take them (cv::Rodrigues).
struct OpenCvExtrinsics {
    glm::dvec3 rvec{0.0}, tvec{0.0};
};
OpenCvExtrinsics openCvExtrinsicsOf(const Pose &pose);

} // namespace overlayd
