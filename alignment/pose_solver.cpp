// SPDX-License-Identifier: Apache-2.0
// solvePose: unproject every pixel through the Camera, solve PnP on the normalized directions with OpenCV (SQPnP,
// refined by Levenberg-Marquardt), reproject through the solved pose to report the error in pixels.
#include "alignment/pose_solver.h"

#include "base/number_text.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <glm/gtc/matrix_access.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace overlayd {

namespace {

// The OpenCV optical axes (x right, y down, z forward) in the internal OpenGL ones; its own inverse.
const glm::dmat3 kFlipYZ = internalFromAxes(CameraAxes::Optical);

std::string pointName(size_t i)
{
    return "point " + std::to_string(i + 1);
}

// The spread of the world points along their principal axes (singular values, largest first).
// The world points' spread along their principal axes (singular values of the centred points, largest first), their
// centroid, and the axis of least spread (the normal of their plane when they are coplanar).
struct Spread {
    cv::Vec3d values;
    glm::dvec3 centroid{0.0}, leastAxis{0.0, 0.0, 1.0};
};

Spread spread(const std::vector<Correspondence> &points)
{
    Spread out;
    cv::Mat centred(int(points.size()), 3, CV_64F);
    for (const Correspondence &c : points)
        out.centroid += c.world / double(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        for (int k = 0; k < 3; ++k)
            centred.at<double>(int(i), k) = points[i].world[k] - out.centroid[k];
    cv::Mat values, u, vt;
    cv::SVD::compute(centred, values, u, vt);
    out.values = {values.at<double>(0), values.rows > 1 ? values.at<double>(1) : 0.0,
                  values.rows > 2 ? values.at<double>(2) : 0.0};
    if (vt.rows == 3)
        out.leastAxis = {vt.at<double>(2, 0), vt.at<double>(2, 1), vt.at<double>(2, 2)};
    return out;
}

// The pose in our internal camera frame from OpenCV's solvePnP and its Levenberg-Marquardt refinement. OpenCV
// throws (cv::Exception) on values its assertions refuse; it stays inside this adapter as an error.
Result<Pose> solvePnp(const std::vector<cv::Point3d> &world, const std::vector<cv::Point2d> &normalized,
                      PnpSolver solver)
{
    const cv::Matx33d identity = cv::Matx33d::eye();
    cv::Mat rvec, tvec;
    const int flags = solver == PnpSolver::Iterative ? cv::SOLVEPNP_ITERATIVE
                      : solver == PnpSolver::Ippe    ? cv::SOLVEPNP_IPPE
                                                     : cv::SOLVEPNP_SQPNP;
    cv::Matx33d r;
    try {
        if (!cv::solvePnP(world, normalized, identity, cv::noArray(), rvec, tvec, false, flags))
            return makeError(ErrorCode::NoConvergence, "OpenCV's solvePnP found no pose for these points");
        cv::solvePnPRefineLM(world, normalized, identity, cv::noArray(), rvec, tvec);
        cv::Rodrigues(rvec, r);
    } catch (const cv::Exception &error) {
        return makeError(ErrorCode::NoConvergence, "OpenCV found no pose for these points (" + error.err + ")");
    }
    glm::dmat3 rotation;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            rotation[col][row] = r(row, col);
    const glm::dvec3 translation(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
    return Pose{kFlipYZ * rotation, kFlipYZ * translation};
}

} // namespace

Result<PoseSolution> solvePose(const Camera &camera, const Distortion &distortion,
                               const std::vector<Correspondence> &points, PnpSolver solver)
{
    if (points.size() < kMinCorrespondences || points.size() > kMaxCorrespondences)
        return makeError(ErrorCode::InvalidArgument, "solving a pose needs " + std::to_string(kMinCorrespondences) +
                                                         ".." + std::to_string(kMaxCorrespondences) + " points, got " +
                                                         std::to_string(points.size()));
    if (!camera.projection().isPerspective())
        return makeError(ErrorCode::Unsupported, "an orthographic camera has no pose to solve from pixels (its rays "
                                                 "are parallel)");
    const Spread shape = spread(points);
    const cv::Vec3d s = shape.values;
    if (s[1] <= 1e-9 * std::max(1.0, s[0]))
        return makeError(ErrorCode::DegenerateBasis, "the world points are collinear (or all one point): a pose "
                                                     "needs at least three not on one line");
    const bool coplanar = s[2] <= 1e-9 * s[0];
    if (solver == PnpSolver::Ippe && !coplanar)
        return makeError(ErrorCode::InvalidArgument, "the ippe solver takes coplanar points only (these are not on "
                                                     "one plane): use sqpnp or iterative");
    if (solver == PnpSolver::Iterative && !coplanar && points.size() < 6)
        return makeError(ErrorCode::InvalidArgument, "the iterative solver needs 6 or more points off a plane (its "
                                                     "DLT start): use sqpnp, or add points");

    // The Camera's rays in its own internal frame, then as optical normalized coordinates (x/z, y/z).
    const glm::dmat3 viewRotation(camera.view());
    std::vector<cv::Point3d> world;
    std::vector<cv::Point2d> normalized;
    for (size_t i = 0; i < points.size(); ++i) {
        auto ray = camera.unproject(points[i].pixel);
        if (!ray)
            return makeError(ray.error().code, pointName(i) + ": " + ray.error().message);
        const glm::dvec3 optical = kFlipYZ * (viewRotation * ray->direction);
        if (optical.z <= 1e-12)
            return makeError(ErrorCode::InvalidArgument, pointName(i) + ": its pixel looks 90 degrees or more away "
                                                                        "from the optical axis");
        world.emplace_back(points[i].world.x, points[i].world.y, points[i].world.z);
        normalized.emplace_back(optical.x / optical.z, optical.y / optical.z);
    }

    auto pose = solvePnp(world, normalized, solver);
    if (!pose)
        return pose.error();
    PoseSolution solution;
    solution.pose = *pose;

    auto solved = Camera::create(solution.pose, camera.projection(), distortion, camera.viewport());
    if (!solved)
        return makeError(solved.error().code, "the solved pose: " + solved.error().message);
    double sum = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        const ProjectedPoint p = solved->project(points[i].world);
        const double error = p.status == PointStatus::Clipped ? INFINITY : glm::length(p.pixel - points[i].pixel);
        solution.errorsPx.push_back(error);
        sum += error * error;
        if (p.status == PointStatus::Clipped)
            solution.warnings.push_back(pointName(i) + " is behind the solved camera: the points do not fit one pose");
    }
    solution.rmsPx = std::sqrt(sum / double(points.size()));
    // Nothing a user clicks lies outside the image: such a pixel is mistyped, or its u and v are swapped.
    const Viewport &viewport = camera.viewport();
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec2 &px = points[i].pixel;
        if (!(px.x >= -0.5 && px.x <= viewport.frameWidth() - 0.5 && px.y >= -0.5 &&
              px.y <= viewport.frameHeight() - 0.5)) {
            const glm::dvec2 user = viewport.toUser(px);
            solution.warnings.push_back(pointName(i) + "'s pixel (" + shortNumber(user.x, 10) + ", " +
                                        shortNumber(user.y, 10) + ") is outside the " +
                                        std::to_string(viewport.frameWidth()) + "x" +
                                        std::to_string(viewport.frameHeight()) + " image");
        }
    }
    const bool flat = s[2] <= 1e-3 * s[0];
    // Marks on a floor seen from under it: the mirrored pose that swapped u and v (a transposed image) fit. The
    // plane's up side is its normal's with z > 0; a plane steeper than kMaxUpPlaneTiltDeg (a wall) has none.
    const glm::dvec3 up = shape.leastAxis.z < 0.0 ? -shape.leastAxis : shape.leastAxis;
    if (flat && up.z >= std::cos(glm::radians(kMaxUpPlaneTiltDeg)) &&
        glm::dot(solved->position() - shape.centroid, up) < 0.0)
        solution.warnings.push_back("the camera is below the plane of the points: are u and v swapped?");
    if (coplanar && points.size() < 6)
        solution.warnings.push_back("the points are coplanar and few: a mirrored pose fits them too; add points "
                                    "off their plane or spread them wider");
    // A flat set seen edge-on: its pixels barely change as the pose tilts about the plane, so the tilt is guesswork.
    if (flat) {
        const glm::dvec3 toPoints = shape.centroid - solved->position();
        const double elevation =
            glm::degrees(std::asin(std::min(1.0, std::abs(glm::dot(glm::normalize(toPoints), shape.leastAxis)))));
        if (elevation < kMinPlaneElevationDeg)
            solution.warnings.push_back("the points' plane is seen nearly edge-on (" + std::to_string(elevation) +
                                        " degrees above it): the camera's tilt is poorly determined; add points "
                                        "off the plane, or nearer the camera");
    }
    if (solution.rmsPx > kLargeRmsPx)
        solution.warnings.push_back("the RMS reprojection error is " + std::to_string(solution.rmsPx) +
                                    " px: a point is mismatched, or the intrinsics or lens do not fit the camera");
    return solution;
}

OpenCvExtrinsics openCvExtrinsicsOf(const Pose &pose)
{
    const glm::dmat3 flip = internalFromAxes(CameraAxes::Optical); // its own inverse
    const glm::dmat3 rotation = flip * pose.rotation;
    cv::Matx33d r;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            r(row, column) = rotation[column][row];
    cv::Vec3d rvec;
    cv::Rodrigues(r, rvec);
    return {glm::dvec3(rvec[0], rvec[1], rvec[2]), flip * pose.translation};
}

} // namespace overlayd
