// SPDX-License-Identifier: Apache-2.0
// Reverse-camera guide lines: the ground track of a car-like vehicle for a steering angle (Ackermann geometry).
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "overlay/shapes/annotation.h"

namespace overlayd {

struct GuideGeometry {
    std::array<std::vector<glm::dvec3>, 2> wheels; // left (+y) and right (-y) rear wheel tracks, from the axle back
    std::vector<std::array<glm::dvec3, 2>> marks;  // per distance mark: left and right wheel positions
};

// In the guide's frame (rear axle centre at the origin, x forward, y left, z up, ground z = 0). With Ackermann
// steering every wheel turns about one centre on the rear axle line, at y = R = wheelbase / tan(steering); backing
// up by arc length s (of the axle centre) turns the body by -s / R about that centre. Straight ahead when the
// steering angle is zero. Distances (length, marks) are measured along the axle centre's path.
GuideGeometry guideGeometry(const GuideLinesShape &shape);

} // namespace overlayd
