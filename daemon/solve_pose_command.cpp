// `overlayd solve-pose`: the camera pose from a file of world points and the pixels they were seen at, printed in
// the config's own pose forms (relative to the camera's mount frame) ready to paste under [camera].
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_inverse.hpp>

#include "alignment/points_file.h"
#include "alignment/pose_solver.h"
#include "daemon/commands.h"
#include "daemon/json_text.h"

namespace overlayd {

namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

std::string vec(const glm::dvec3 &v)
{
    return "[" + jsonNumber(v.x) + ", " + jsonNumber(v.y) + ", " + jsonNumber(v.z) + "]";
}

// OpenCV's rvec of a rotation matrix (Rodrigues' inverse), for `rvec = [...]` in the config.
glm::dvec3 rodrigues(const glm::dmat3 &r)
{
    const double c = std::clamp((r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0, -1.0, 1.0);
    const double angle = std::acos(c);
    const glm::dvec3 axis(r[1][2] - r[2][1], r[2][0] - r[0][2], r[0][1] - r[1][0]); // 2 sin(angle) * axis
    const double s = glm::length(axis);
    if (s > 1e-9)
        return axis * (angle / s);
    if (c > 0.0)
        return glm::dvec3(0.0); // no rotation
    // 180 degrees: the axis from the symmetric part, R = 2 a a^T - I.
    glm::dvec3 a(std::sqrt(std::max(0.0, (r[0][0] + 1.0) / 2.0)), std::sqrt(std::max(0.0, (r[1][1] + 1.0) / 2.0)),
                 std::sqrt(std::max(0.0, (r[2][2] + 1.0) / 2.0)));
    if (a.x > 1e-6) {
        a.y = std::copysign(a.y, r[0][1]);
        a.z = std::copysign(a.z, r[0][2]);
    } else if (a.y > 1e-6) {
        a.z = std::copysign(a.z, r[1][2]);
    }
    return glm::normalize(a) * angle;
}

} // namespace

int solvePoseCommand(const std::string &configPath, const std::string &pointsPath, Logger &logger)
{
    const auto configured = loadCameraLogged(configPath, logger);
    if (!configured)
        return kExitConfigError;
    const Camera *camera = &configured->camera;
    const DaemonConfig *config = &configured->config;
    auto points = alignment::readPointsFile(pointsPath);
    if (!points) {
        logger.error(points.error().message);
        return kExitFailure;
    }
    for (alignment::Correspondence &point : *points)
        point.pixel = camera->viewport().toTopLeft(point.pixel); // the user's origin in, memory order inside
    auto solution = alignment::solvePose(*camera, config->camera.distortion, *points);
    if (!solution) {
        logger.error(cat("solve-pose: ", solution.error().message));
        return kExitFailure;
    }

    // The solved pose maps world to camera; the config's pose maps the mount frame to camera.
    const glm::dmat4 worldFromMount = config->camera.worldFromMount;
    const glm::dmat4 cameraFromMount = solution->pose.viewMatrix() * worldFromMount;
    const glm::dmat3 rotationGl(cameraFromMount);
    const glm::dvec3 translationGl(cameraFromMount[3]);
    const glm::dmat3 flip{1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0}; // OpenGL <-> optical axes
    const glm::dmat3 rotationCv = flip * rotationGl;
    const glm::dvec3 tvec = flip * translationGl;
    const glm::dvec3 position = -glm::transpose(rotationGl) * translationGl;
    // Body axes (x forward, y left, z up) in the mount frame, then ZYX yaw/pitch/roll.
    const glm::dmat3 mountFromGl = glm::transpose(rotationGl);
    const glm::dmat3 mountFromBody = mountFromGl * internalFromAxes(CameraAxes::Body);
    const double pitch = std::asin(std::clamp(-mountFromBody[0][2], -1.0, 1.0));
    const double yaw = std::atan2(mountFromBody[0][1], mountFromBody[0][0]);
    const double roll = std::atan2(mountFromBody[1][2], mountFromBody[2][2]);

    std::string out = "# solve-pose: " + std::to_string(points->size()) + " points, RMS reprojection error " +
                      jsonNumber(solution->rmsPx) + " px\n";
    for (size_t i = 0; i < solution->errorsPx.size(); ++i)
        out += "#   point " + std::to_string(i + 1) + ": " + jsonNumber(solution->errorsPx[i]) + " px\n";
    for (const std::string &warning : solution->warnings)
        out += "# warning: " + warning + "\n";
    out += "# the pose of the camera in its mount frame '" + config->camera.mountFrame + "'; paste under [camera]\n";
    out += "[camera]\nrvec = " + vec(rodrigues(rotationCv)) + "\ntvec = " + vec(tvec) + "\n";
    out += "# the same pose as position + yaw/pitch/roll (degrees):\n# position = " + vec(position) +
           "\n# yaw = " + jsonNumber(yaw * kDegrees) + "\n# pitch = " + jsonNumber(pitch * kDegrees) +
           "\n# roll = " + jsonNumber(roll * kDegrees) + "\n";
    std::fwrite(out.data(), 1, out.size(), stdout);
    for (const std::string &warning : solution->warnings)
        logger.warning(cat("solve-pose: ", warning));
    return kExitOk;
}

} // namespace overlayd
