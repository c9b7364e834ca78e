// SPDX-License-Identifier: Apache-2.0
// Ackermann ground tracks for the reverse-camera guide lines.
#include "overlay/shapes/guide_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

namespace overlayd {

namespace {

// Chords stray at most this far from the arc they stand for: a chord c of a circle of radius r leaves it by
// c^2 / (8 r) at its middle. Steps between 2 cm and 50 cm (a straight track, or one through a distorting lens, is
// curved by the projection itself). A live steering angle redraws the tracks every frame, so fewer chords count.
constexpr double kSagittaMetres = 0.0003;
constexpr double kMinStepMetres = 0.02, kMaxStepMetres = 0.5;

double stepFor(double tanSteering, const GuideLinesShape &shape)
{
    if (std::abs(tanSteering) < 1e-12)
        return kMaxStepMetres;
    const double innerRadius = std::abs(shape.wheelbase / tanSteering) - 0.5 * shape.trackWidth;
    if (innerRadius <= 0.0)
        return kMinStepMetres;
    return std::clamp(std::sqrt(8.0 * innerRadius * kSagittaMetres), kMinStepMetres, kMaxStepMetres);
}

// Where the body point p (at the start) is after the axle centre backed up by `distance` metres.
glm::dvec3 afterReversing(const glm::dvec3 &p, double distance, double tanSteering, double wheelbase)
{
    if (std::abs(tanSteering) < 1e-12)
        return p - glm::dvec3(distance, 0.0, 0.0);
    const double radius = wheelbase / tanSteering; // signed: positive turns left, centre at (0, radius)
    const double angle = -distance / radius;
    const double dx = p.x, dy = p.y - radius;
    return {dx * std::cos(angle) - dy * std::sin(angle), radius + dx * std::sin(angle) + dy * std::cos(angle), p.z};
}

} // namespace

GuideGeometry guideGeometry(const GuideLinesShape &shape)
{
    const double tanSteering = std::tan(glm::radians(shape.steeringDeg));
    const std::array<glm::dvec3, 2> wheels{glm::dvec3(0.0, 0.5 * shape.trackWidth, 0.0),
                                           glm::dvec3(0.0, -0.5 * shape.trackWidth, 0.0)};
    GuideGeometry out;
    const int steps = std::max(1, int(std::ceil(shape.length / stepFor(tanSteering, shape))));
    for (int side = 0; side < 2; ++side) {
        for (int i = 0; i <= steps; ++i)
            out.wheels[side].push_back(
                afterReversing(wheels[side], shape.length * i / steps, tanSteering, shape.wheelbase));
    }
    for (double distance : shape.distanceMarks) {
        if (distance < 0.0 || distance > shape.length)
            continue;
        out.marks.push_back({afterReversing(wheels[0], distance, tanSteering, shape.wheelbase),
                             afterReversing(wheels[1], distance, tanSteering, shape.wheelbase)});
    }
    return out;
}

} // namespace overlayd
