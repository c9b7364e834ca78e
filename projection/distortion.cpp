// SPDX-License-Identifier: Apache-2.0
// OpenCV's distortion models (calib3d projectPoints, fisheye::projectPoints) and their numerical inverse.
#include "distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>

#include "distortion_formulas.h"

namespace overlayd {

int coefficientCount(DistortionModel model)
{
    switch (model) {
    case DistortionModel::None:
        return 0;
    case DistortionModel::RadialTangential:
        return 5;
    case DistortionModel::Rational:
        return 8;
    case DistortionModel::Fisheye:
        return 4;
    }
    return 0;
}

Status validateDistortion(const Distortion &distortion)
{
    for (double c : distortion.coeffs)
        if (!std::isfinite(c))
            return makeError(ErrorCode::InvalidArgument, "distortion coefficients must be finite");
    for (std::size_t i = coefficientCount(distortion.model); i < distortion.coeffs.size(); ++i)
        if (distortion.coeffs[i] != 0.0)
            return makeError(ErrorCode::InvalidArgument, "distortion model takes " +
                                                             std::to_string(coefficientCount(distortion.model)) +
                                                             " coefficients; extra ones are not zero");
    if (!(distortion.fieldDeg >= 0.0 && distortion.fieldDeg < kMaxFisheyeFieldDeg))
        return makeError(ErrorCode::InvalidArgument, "a fisheye's field of view must be in (0, 360) degrees");
    if (distortion.fieldDeg != 0.0 && distortion.model != DistortionModel::Fisheye)
        return makeError(ErrorCode::InvalidArgument,
                         "a field of view is declared for fisheye (equidistant) lenses only");
    return Ok{};
}

namespace {

// The distorted radius as a function of the undistorted one, along one direction (tangential terms aside).
double radialImage(const Distortion &d, double r)
{
    if (d.model == DistortionModel::Fisheye)
        return DistortionFormulas::fisheyeTheta(d.coeffs, std::atan(r));
    const auto &c = d.coeffs;
    const double r2 = r * r;
    return r * (1.0 + c[0] * r2 + c[1] * r2 * r2 + c[4] * r2 * r2 * r2) /
           (1.0 + c[5] * r2 + c[6] * r2 * r2 + c[7] * r2 * r2 * r2);
}

} // namespace

glm::dvec2 distortNormalized(const Distortion &distortion, const glm::dvec2 &xy)
{
    switch (distortion.model) {
    case DistortionModel::None:
        return xy;
    case DistortionModel::RadialTangential:
        return DistortionFormulas::radialTangential(distortion.coeffs, xy.x, xy.y);
    case DistortionModel::Rational:
        return DistortionFormulas::rational(distortion.coeffs, xy.x, xy.y);
    case DistortionModel::Fisheye:
        return DistortionFormulas::fisheye(distortion.coeffs, xy.x, xy.y);
    }
    return xy;
}

Result<glm::dvec2> undistortNormalized(const Distortion &distortion, const glm::dvec2 &distorted)
{
    if (distortion.model == DistortionModel::None)
        return distorted;
    glm::dvec2 x = distorted;
    const double tolerance = 1e-12 * std::max(1.0, glm::length(distorted));
    for (int iteration = 0; iteration < 100; ++iteration) {
        const glm::dvec2 residual = distortNormalized(distortion, x) - distorted;
        if (glm::length(residual) <= tolerance)
            return x;
        // Central-difference Jacobian: the models are smooth, and the answer is checked against the residual.
        const double h = 1e-7 * std::max(1.0, glm::length(x));
        const glm::dvec2 dx = (distortNormalized(distortion, x + glm::dvec2(h, 0)) -
                               distortNormalized(distortion, x - glm::dvec2(h, 0))) /
                              (2.0 * h);
        const glm::dvec2 dy = (distortNormalized(distortion, x + glm::dvec2(0, h)) -
                               distortNormalized(distortion, x - glm::dvec2(0, h))) /
                              (2.0 * h);
        const glm::dmat2 jacobian(dx, dy);
        const double det = glm::determinant(jacobian);
        if (!std::isfinite(det) || std::abs(det) < 1e-300)
            break;
        x -= glm::inverse(jacobian) * residual;
        if (!std::isfinite(x.x) || !std::isfinite(x.y))
            break;
    }
    return makeError(ErrorCode::NoConvergence, "undistortion did not converge (point outside the lens's field?)");
}

namespace {

// The scan's step is 0.01 degrees from the axis; a model that grows at every step up to kScanEnd keeps growing to
// just short of the back axis, where a direction has no azimuth left and the scan stops.
constexpr double kNarrowMaxAngle = 89.0 * M_PI / 180.0;
constexpr int kNarrowSteps = 8900;
constexpr int kScanSteps = 18000 - 1; // 179.99 degrees

double scanAngle(int i)
{
    return kNarrowMaxAngle * i / kNarrowSteps;
}

} // namespace

namespace {

double scanFisheye(const Distortion &distortion, int steps)
{
    double previous = 0.0;
    for (int i = 1; i <= steps; ++i) {
        const double image = DistortionFormulas::fisheyeTheta(distortion.coeffs, scanAngle(i));
        // The peak lies between steps i - 2 and i: i - 2 is the last step known to be before it.
        if (!(image > previous))
            return scanAngle(std::max(i - 2, 0));
        previous = image;
    }
    return scanAngle(steps);
}

} // namespace

double fisheyeMaxAngle(const Distortion &distortion)
{
    return scanFisheye(distortion, kScanSteps);
}

double fisheyeFieldAngle(const Distortion &distortion)
{
    const double declared = distortion.fieldDeg > 0.0 ? 0.5 * distortion.fieldDeg * M_PI / 180.0 : M_PI;
    const double model =
        distortion.fieldDeg > 180.0 ? fisheyeMaxAngle(distortion) : scanFisheye(distortion, kNarrowSteps);
    return std::min(model, declared);
}

double monotonicRadius(const Distortion &distortion)
{
    // Scan outwards in small steps of the viewing angle, up to just short of 90 degrees off-axis: the radius
    // X/Z ends there. A fisheye is scanned on its angle (fisheyeFieldAngle); when its field goes past 90 degrees
    // every radius in front of the camera is valid.
    if (distortion.model == DistortionModel::None)
        return std::tan(kNarrowMaxAngle);
    if (distortion.model == DistortionModel::Fisheye) {
        const double angle = fisheyeFieldAngle(distortion);
        return angle >= M_PI / 2 ? std::numeric_limits<double>::infinity() : std::tan(angle);
    }
    double previous = 0.0;
    for (int i = 1; i <= kNarrowSteps; ++i) {
        const double r = std::tan(scanAngle(i));
        const double image = radialImage(distortion, r);
        if (!(image > previous))
            return std::tan(scanAngle(i - 1));
        previous = image;
    }
    return std::tan(kNarrowMaxAngle);
}

Result<double> undistortFisheyeAngle(const Distortion &distortion, double thetaD, double maxAngle)
{
    // theta_d(theta) grows on [0, maxAngle] (that is what maxAngle means), so bisection cannot miss the root;
    // Newton's steps speed it up where they stay inside the bracket.
    // The rim itself is reached by projecting points on the field's edge: allow its rounding, no more.
    const double rim = DistortionFormulas::fisheyeTheta(distortion.coeffs, maxAngle);
    if (!(thetaD >= 0.0) || thetaD > rim * (1.0 + 1e-12))
        return makeError(ErrorCode::NoConvergence, "pixel lies outside the lens model's valid field");
    if (thetaD >= rim)
        return maxAngle;
    double lo = 0.0, hi = maxAngle, theta = std::min(thetaD, maxAngle);
    for (int iteration = 0; iteration < 200 && hi - lo > 0.0; ++iteration) {
        const double f = DistortionFormulas::fisheyeTheta(distortion.coeffs, theta) - thetaD;
        if (f == 0.0)
            break;
        (f < 0.0 ? lo : hi) = theta;
        const double h = 1e-7;
        const double slope = (DistortionFormulas::fisheyeTheta(distortion.coeffs, theta + h) -
                              DistortionFormulas::fisheyeTheta(distortion.coeffs, theta - h)) /
                             (2.0 * h);
        const double newton = theta - f / slope;
        const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
        if (next == theta)
            break;
        theta = next;
    }
    return theta;
}

} // namespace overlayd
