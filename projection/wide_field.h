// SPDX-License-Identifier: Apache-2.0
// The field of a fisheye that sees behind the camera plane: which parts of a segment it draws, on the angle.
//
// Past 90 degrees from the axis no X/Z radius exists, so neither the near plane nor the lens's X/Z cone can bound
// what is drawn. The field is instead: outside the near sphere |P| < near, on the near side of the far plane (if
// any), and outside the cone about the back axis that the model does not reach (theta > Lens::validAngle).
#pragma once

#include <array>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace overlayd {

// Up to three parameter intervals [t0, t1] of a segment a + t (b - a), t in [0, 1], in order.
struct SegmentPieces {
    std::array<std::array<double, 2>, 3> ranges{};
    int count = 0;
};

struct WideField {
    glm::dmat2 toNormalized{1.0}; // clip (x, y, w) -> optical (X, Y), as PointPath's
    glm::dvec2 toNormalizedW{0.0};
    double backSlope2 = 0.0; // behind the plane, in the field while |(X, Y)|^2 >= backSlope2 Z^2
    double near2 = 0.0;
    bool hasFar = false;

    // Optical-frame coordinates (X, Y, Z) of a clip-space point of the pinhole projection (Z = w).
    glm::dvec3 optical(const glm::dvec4 &clip) const;
    // The same test as the point kernel's (projectWideFisheye).
    bool inside(const glm::dvec4 &clip) const;
    SegmentPieces pieces(const glm::dvec4 &a, const glm::dvec4 &b) const;
};

} // namespace overlayd
