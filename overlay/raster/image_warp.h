// SPDX-License-Identifier: Apache-2.0
// Warps an image's premultiplied RGBA pixels onto a layer (OpenCV's warpPerspective, bilinear; what falls outside the
// image is transparent, so its edges come out anti-aliased), over what the layer holds.
#pragma once

#include <array>

#include <glm/vec2.hpp>

#include "overlay/raster/overlay_layer.h"
#include "overlay/shapes/annotation.h"

namespace overlayd {

// `quad`: the image's top-left, top-right, bottom-right and bottom-left outer corners in the layer's pixels (pixel
// centres at integer coordinates). opacity scales the whole image. An image shrunk to less than half its size is
// first reduced by area averaging, so that a large logo drawn small does not shimmer. False (nothing drawn) for a quad
// that is not a convex quadrilateral of some area (a plane seen edge-on).
bool warpImage(const ImagePixels &image, const std::array<glm::dvec2, 4> &quad, double opacity, OverlayLayer &layer);

} // namespace overlayd
