// SPDX-License-Identifier: Apache-2.0
// Annotation -> 2D primitives in memory-order pixels, through the camera (clipped, curved through the lens).
#pragma once

#include <glm/mat4x4.hpp>

#include "overlay/shapes/annotation.h"
#include "overlay/shapes/primitives.h"
#include "projection/camera.h"

namespace overlayd {

// Appends the annotation's primitives to `out`. worldFromFrame is the world matrix of the annotation's frame.
void buildPrimitives(const Annotation &annotation, const glm::dmat4 &worldFromFrame, const Camera &camera,
                     DrawList &out);

bool isScreenText(const Annotation &annotation);

} // namespace overlayd
