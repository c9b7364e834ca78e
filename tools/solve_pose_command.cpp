// SPDX-License-Identifier: Apache-2.0
// `overlayd solve-pose`: the camera pose from a file of world points and the pixels they were seen at, printed in
// the config's own pose forms (relative to the camera's mount frame) ready to paste under [camera].
#include <cmath>
#include <cstdio>

#include "alignment/points_file.h"
#include "alignment/pose_solver.h"
#include "base/json_text.h"
#include "base/number_text.h"
#include "config/live_drop_in.h"
#include "tools/commands.h"

namespace overlayd {

namespace {

// What the printed numbers are rounded to: far below what clicked pixels can tell, far above the solver's noise.
constexpr int kPixelErrorDecimals = 3; // a thousandth of a pixel
constexpr int kPoseDecimals = 7;       // metres, degrees and rvec's radians: 0.1 um, 1e-7 degree (or radian)

std::string number(double value, int decimals = kPoseDecimals)
{
    return jsonNumber(roundedTo(value, decimals));
}

std::string vec(const glm::dvec3 &v, int decimals = kPoseDecimals)
{
    return "[" + number(v.x, decimals) + ", " + number(v.y, decimals) + ", " + number(v.z, decimals) + "]";
}

} // namespace

int solvePoseCommand(const std::string &configPath, const std::string &pointsPath, const std::string &solver,
                     bool write, Logger &logger)
{
    const auto configured = loadCameraLogged(configPath, logger);
    if (!configured)
        return kExitConfigError;
    const Camera *camera = &configured->camera;
    const DaemonConfig *config = &configured->config;
    auto points = readPointsFile(pointsPath);
    if (!points) {
        logger.error(points.error().message);
        return kExitFailure;
    }
    for (Correspondence &point : *points)
        point.pixel = camera->viewport().toTopLeft(point.pixel); // the user's origin in, memory order inside
    const PnpSolver pnp = solver == "iterative" ? PnpSolver::Iterative
                          : solver == "ippe"    ? PnpSolver::Ippe
                                                : PnpSolver::Sqpnp;
    auto solution = solvePose(*camera, config->camera.distortion, *points, pnp);
    if (!solution) {
        logger.error(cat("solve-pose: ", solution.error().message));
        return kExitFailure;
    }

    // The solved pose maps world to camera; the config's pose maps the mount frame to camera.
    const glm::dmat4 cameraFromMount = solution->pose.viewMatrix() * config->camera.worldFromMount;
    const Pose mountPose{glm::dmat3(cameraFromMount), glm::dvec3(cameraFromMount[3])};
    const OpenCvExtrinsics extrinsics = openCvExtrinsicsOf(mountPose);
    const YawPitchRoll ypr = yawPitchRollOf(mountPose);

    // Written before anything is printed: the output says where the pose went only once it is there.
    std::string written;
    if (write) {
        CameraSpec solved = config->camera;
        solved.pose = mountPose;
        auto wrote = writeLiveDropIn(configPath, solved, "solve-pose --write");
        if (!wrote) {
            logger.error(cat("solve-pose: ", wrote.error().message));
            return kExitFailure;
        }
        written = *wrote;
    }

    std::string out = "# solve-pose: " + std::to_string(points->size()) + " points, RMS reprojection error " +
                      number(solution->rmsPx, kPixelErrorDecimals) + " px\n";
    for (size_t i = 0; i < solution->errorsPx.size(); ++i)
        out +=
            "#   point " + std::to_string(i + 1) + ": " + number(solution->errorsPx[i], kPixelErrorDecimals) + " px\n";
    for (const std::string &warning : solution->warnings)
        out += "# warning: " + warning + "\n";
    out += "# the pose of the camera in its mount frame '" + config->camera.mountFrame +
           (write ? "'; written to " + written + " (read after " + configPath + ")\n"
                  : "'; paste under [camera] in place of its pose keys (one pose form per camera), or run with "
                    "--write\n");
    out += "[camera]\nrvec = " + vec(extrinsics.rvec) + "\ntvec = " + vec(extrinsics.tvec) + "\n";
    out += "# the same pose as position + yaw/pitch/roll (degrees):\n# position = " + vec(ypr.position) +
           "\n# yaw = " + number(ypr.yawDeg) + "\n# pitch = " + number(ypr.pitchDeg) +
           "\n# roll = " + number(ypr.rollDeg) + "\n";
    std::fwrite(out.data(), 1, out.size(), stdout);
    for (const std::string &warning : solution->warnings)
        logger.warning(cat("solve-pose: ", warning));
    if (write)
        logger.notice(cat("solve-pose: the pose is in ", written, " (read after ", configPath,
                          "; a running daemon takes it on reload)"));
    return kExitOk;
}

} // namespace overlayd
