// SPDX-License-Identifier: Apache-2.0
// The synthetic source's 2D test patterns, drawn in RGB (the converter encodes them into the stream's format).
#pragma once

#include <cstdint>

#include "media/convert/images.h"

namespace overlayd {

// The eight 100% colour bars, left to right: white, yellow, cyan, green, magenta, red, blue, black. Bar i spans
// columns [barEdge(i), barEdge(i + 1)); edges are even so that no 4:2:x macropixel straddles two bars.
RgbImage colourBars(unsigned width, unsigned height);
unsigned barEdge(unsigned bar, unsigned width);
inline constexpr uint8_t kBarColours[8][3] = {{255, 255, 255}, {255, 255, 0}, {0, 255, 255}, {0, 255, 0},
                                              {255, 0, 255},   {255, 0, 0},   {0, 0, 255},   {0, 0, 0}};

// White and black squares of squarePx pixels; the top-left square is white.
RgbImage checkerboard(unsigned width, unsigned height, unsigned squarePx);

// Red ramps across, green down, blue along the diagonal; the picture scrolls left by kGradientStepPx per frame.
inline constexpr unsigned kGradientStepPx = 4;
void movingGradient(RgbImage &image, uint64_t frame);

// Uniform random bytes from a splitmix64 stream seeded by (seed, frame): the same on every compiler and machine.
void noise(RgbImage &image, uint64_t seed, uint64_t frame);

} // namespace overlayd
