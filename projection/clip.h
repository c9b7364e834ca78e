// SPDX-License-Identifier: Apache-2.0
// Clipping in homogeneous clip space, before the divide by w: points, segments and polygons.
//
// Each plane is a 4-vector p; a clip-space point c is inside when dot(p, c) >= 0. Clipping before the divide
// is what keeps points behind the camera from being mirrored onto the image (they have w < 0).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "projection.h"

namespace overlayd {

// Rectangle in NDC x, y for the side planes; a guard band wider than [-1,1] lets lines run past the window edge.
struct NdcBounds {
    double xMin = -1, xMax = 1, yMin = -1, yMax = 1;
};

class ClipPlanes
{
public:
    // Near (always), far (when the projection has one), and the four side planes at `sides`.
    ClipPlanes(DepthRange depth, bool far, const NdcBounds &sides);

    bool inside(const glm::dvec4 &clip) const;
    // The parameter interval [t0, t1] of a + t (b - a), t in [0, 1], inside every plane; nothing if empty.
    std::optional<std::array<double, 2>> clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const;
    // Sutherland-Hodgman against every plane; out receives the clipped polygon (empty when nothing is left).
    void clipPolygon(std::span<const glm::dvec4> polygon, std::vector<glm::dvec4> &out) const;

    std::span<const glm::dvec4> planes() const { return {planes_.data(), count_}; }

private:
    std::array<glm::dvec4, 6> planes_{};
    std::size_t count_ = 0;
};

} // namespace overlayd
