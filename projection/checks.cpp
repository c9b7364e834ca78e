// SPDX-License-Identifier: Apache-2.0
// Shared validation helpers for the projection builders.
#include "checks.h"

#include "base/number_text.h"
#include <algorithm>
#include <cstdio>

#include <glm/mat3x3.hpp>

namespace overlayd {

bool Checks::finite(const glm::dvec3 &v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool Checks::finite(const glm::dmat3 &m)
{
    return finite(m[0]) && finite(m[1]) && finite(m[2]);
}

std::string Checks::str(double v)
{
    return shortNumber(v, 9);
}

std::string Checks::str(const glm::dvec3 &v)
{
    return "(" + str(v.x) + ", " + str(v.y) + ", " + str(v.z) + ")";
}

double Checks::orthonormalityError(const glm::dmat3 &r)
{
    const glm::dmat3 gram = glm::transpose(r) * r;
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            worst = std::max(worst, std::abs(gram[c][row] - (c == row ? 1.0 : 0.0)));
    return worst;
}

Status Checks::requireRotation(const glm::dmat3 &r, const char *what)
{
    if (!finite(r))
        return makeError(ErrorCode::InvalidArgument, std::string(what) + " has a non-finite element");
    const double err = orthonormalityError(r);
    if (err > kOrthonormal)
        return makeError(ErrorCode::NotOrthonormal, std::string(what) + " is not orthonormal (|R^T R - I| = " +
                                                        str(err) + ", tolerance " + str(kOrthonormal) + ")");
    if (glm::determinant(r) < 0.0)
        return makeError(ErrorCode::NotOrthonormal,
                         std::string(what) + " is a reflection (determinant -1), not a rotation");
    return Ok{};
}

} // namespace overlayd
