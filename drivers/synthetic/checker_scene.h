// SPDX-License-Identifier: Apache-2.0
// The synthetic 3D scene: a checkerboard on the ground plane z = 0, ray-traced per pixel through the stream's
// camera, so that a grid overlay of the same spacing must land on its edges without trusting the overlay path.
#pragma once

#include <cstdint>

#include "media/convert/images.h"
#include "projection/camera.h"

namespace overlayd {

// Squares have corners at multiples of squareMetres; square (i, j) = (floor(x / s), floor(y / s)) is dark when
// i + j is odd. Pixels whose ray misses the ground (above the horizon, or outside the lens's valid field) are sky.
inline constexpr uint8_t kSceneLight[3] = {150, 150, 150};
inline constexpr uint8_t kSceneDark[3] = {60, 60, 60};
inline constexpr uint8_t kSceneSky[3] = {140, 170, 200};
inline constexpr unsigned kSceneSupersampling = 3; // per axis, where a pixel is not inside one square

// The camera's viewport must cover width x height; rows are in memory order whatever the viewport's origin.
RgbImage renderCheckerScene(const Camera &camera, unsigned width, unsigned height, double squareMetres);

} // namespace overlayd
