// OpenCV's distortion models (calib3d projectPoints, fisheye::projectPoints) and their numerical inverse.
#include "distortion.h"

#include <cmath>

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
    return Ok{};
}

namespace {

// The distorted radius as a function of the undistorted one, along one direction (tangential terms aside).
double radialImage(const Distortion &d, double r)
{
    if (d.model == DistortionModel::Fisheye)
        return formulas::fisheyeTheta(d.coeffs, std::atan(r));
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
        return formulas::radialTangential(distortion.coeffs, xy.x, xy.y);
    case DistortionModel::Rational:
        return formulas::rational(distortion.coeffs, xy.x, xy.y);
    case DistortionModel::Fisheye:
        return formulas::fisheye(distortion.coeffs, xy.x, xy.y);
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

double monotonicRadius(const Distortion &distortion)
{
    // Scan outwards in small steps of the viewing angle, up to just short of 90 degrees off-axis.
    constexpr double kMaxAngle = 89.0 * M_PI / 180.0;
    constexpr int kSteps = 8900;
    if (distortion.model == DistortionModel::None)
        return std::tan(kMaxAngle);
    double previous = 0.0;
    for (int i = 1; i <= kSteps; ++i) {
        const double r = std::tan(kMaxAngle * i / kSteps);
        const double image = radialImage(distortion, r);
        if (!(image > previous))
            return std::tan(kMaxAngle * (i - 1) / kSteps);
        previous = image;
    }
    return std::tan(kMaxAngle);
}

} // namespace overlayd
