// SPDX-License-Identifier: Apache-2.0
// Where an image annotation lands in the frame: its four outer corners in memory-order pixels (pixel centres at
// integer coordinates), for the renderer to warp the image's pixels into.
#pragma once

#include <array>
#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "overlay/shapes/annotation.h"
#include "projection/camera.h"

namespace overlayd {

// The image's top-left, top-right, bottom-right and bottom-left corners (its outer edges). A world image with a
// corner that does not project (behind the camera, beyond far) gives nullopt: it is not drawn rather than drawn
// wrongly. The inside of a world image follows the homography of its corners (exact for a lens without
// distortion; through a distorting lens only the corners are exact).
std::optional<std::array<glm::dvec2, 4>> imageQuad(const ImageShape &shape, const glm::dmat4 &worldFromFrame,
                                                   const Camera &camera);

} // namespace overlayd
