// SPDX-License-Identifier: Apache-2.0
// The constants of the per-point path from clip space to pixels, composed once per Camera (see point_kernel.h).
#pragma once

#include <array>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>

namespace overlayd {

struct PointPath {
    glm::dmat2 toNormalized{1.0};  // (clip.x, clip.y, clip.w) -> w * normalized optical coordinates
    glm::dvec2 toNormalizedW{0.0}; //   (for no lens: w * NDC)
    glm::dmat2 toPixel{1.0};       // (distorted) normalized coordinates or NDC -> pixel
    glm::dvec2 toPixelOffset{0.0};
    double validRadius2 = 0.0;
    // A fisheye that sees more than 180 degrees (Lens::seesBehind): the angle from the axis decides, not X/Z.
    // Points count as in front down to the near sphere |P| = near; behind the camera plane, a point is in the
    // field while |(X, Y)|^2 >= backSlope2 Z^2 (outside the cone about the back axis the lens cannot see).
    bool wide = false;
    double backSlope2 = 0.0;
    double near2 = 0.0;
    double nearW = 0.0; // the near test is z + nearW * w >= 0: 0 for ZeroToOne, 1 for MinusOneToOne
    bool hasFar = false;
    glm::dvec2 scissorMin{0.0}, scissorMax{0.0};
    std::array<double, 8> coeffs{}; // the lens's distortion coefficients (all 0 without a lens)
};

} // namespace overlayd
