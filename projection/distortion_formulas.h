// SPDX-License-Identifier: Apache-2.0
// Per-point distortion formulas, inline: shared by distortNormalized and Camera's batch loops so both agree.
#pragma once

#include <array>
#include <cmath>

#include <glm/vec2.hpp>

namespace overlayd {

// The formulas, one static function each.
struct DistortionFormulas {
    // OpenCV's 5-coefficient model (k1, k2, p1, p2, k3). Identical to rational() with k4 = k5 = k6 = 0, whose
    // denominator is then exactly 1, minus the division.
    static glm::dvec2 radialTangential(const std::array<double, 8> &c, double x, double y)
    {
        const double k1 = c[0], k2 = c[1], p1 = c[2], p2 = c[3], k3 = c[4];
        const double r2 = x * x + y * y;
        const double r4 = r2 * r2, r6 = r4 * r2;
        const double radial = 1.0 + k1 * r2 + k2 * r4 + k3 * r6;
        const double a1 = 2.0 * x * y;
        return {x * radial + p1 * a1 + p2 * (r2 + 2.0 * x * x), y * radial + p1 * (r2 + 2.0 * y * y) + p2 * a1};
    }

    // OpenCV's 8-coefficient rational model (k1, k2, p1, p2, k3, k4, k5, k6), in OpenCV's order of operations.
    static glm::dvec2 rational(const std::array<double, 8> &c, double x, double y)
    {
        const auto [k1, k2, p1, p2, k3, k4, k5, k6] = c;
        const double r2 = x * x + y * y;
        const double r4 = r2 * r2, r6 = r4 * r2;
        const double radial = (1.0 + k1 * r2 + k2 * r4 + k3 * r6) / (1.0 + k4 * r2 + k5 * r4 + k6 * r6);
        const double a1 = 2.0 * x * y;
        return {x * radial + p1 * a1 + p2 * (r2 + 2.0 * x * x), y * radial + p1 * (r2 + 2.0 * y * y) + p2 * a1};
    }

    // theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8).
    static double fisheyeTheta(const std::array<double, 8> &c, double theta)
    {
        const double t2 = theta * theta;
        return theta * (1.0 + t2 * (c[0] + t2 * (c[1] + t2 * (c[2] + t2 * c[3]))));
    }

    // OpenCV's fisheye (equidistant) model on theta = atan(r).
    static glm::dvec2 fisheye(const std::array<double, 8> &c, double x, double y)
    {
        const double r = std::sqrt(x * x + y * y);
        // OpenCV uses the same guard: below 1e-8 the ratio theta_d / r tends to 1.
        const double scale = r > 1e-8 ? fisheyeTheta(c, std::atan(r)) / r : 1.0;
        return {x * scale, y * scale};
    }
};

} // namespace overlayd
