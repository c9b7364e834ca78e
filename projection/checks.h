// SPDX-License-Identifier: Apache-2.0
// Shared validation helpers: every builder refuses NaN/inf and near-zero vectors with a clear message.
#pragma once

#include <cmath>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "base/result.h"

namespace overlayd {

// Checks every builder shares: a class of static functions, so that call sites read Checks::finite(v).
struct Checks {
    // Relative tolerance below which a vector counts as zero or two directions as parallel.
    static constexpr double kDegenerate = 1e-9;
    // How far R^T R may stray from the identity before R is refused as "not a rotation".
    static constexpr double kOrthonormal = 1e-6;

    static bool finite(const glm::dvec3 &v);
    static bool finite(const glm::dmat3 &m);
    static std::string str(const glm::dvec3 &v);
    static std::string str(double v);

    // The largest |(R^T R - I)_ij|: zero for a rotation or reflection.
    static double orthonormalityError(const glm::dmat3 &r);
    // Refuses anything but a proper rotation (orthonormal, determinant +1); `what` names the value in the message.
    static Status requireRotation(const glm::dmat3 &r, const char *what);
};

} // namespace overlayd
