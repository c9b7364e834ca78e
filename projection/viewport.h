// SPDX-License-Identifier: Apache-2.0
// Viewport (the viewing pipeline's viewport transformation): NDC -> pixels of a window placed on a frame.
//
// Pixel convention: pixel (i, j) is the unit square centred on (i, j), so a frame of W x H pixels spans
// [-0.5, W - 0.5] x [-0.5, H - 0.5]. This is OpenCV's and ROS's convention (cx, cy are used as given); the viewing
// pipeline's corner-based screen coordinates are ours + 0.5. With Origin::TopLeft, row 0 is the top row and rows grow
// downwards; with Origin::BottomLeft, row 0 is the bottom row and rows grow upwards. Window position and scissor
// are given in the same convention as the pixels.
#pragma once

#include <optional>

#include <glm/vec2.hpp>

#include "base/result.h"

namespace overlayd {

enum class Origin { TopLeft, BottomLeft };

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;

    bool contains(const PixelRect &inner) const;
    bool operator==(const PixelRect &) const = default;
};

struct ViewportSpec {
    int frameWidth = 0, frameHeight = 0;
    std::optional<PixelRect> window{}; // posx, posy, xres, yres; the whole frame when unset
    Origin origin = Origin::TopLeft;
    double pixelAspect = 1.0;           // horizontal / vertical pixel spacing (non-square pixels)
    std::optional<PixelRect> scissor{}; // limits drawing; the window when unset

    bool operator==(const ViewportSpec &) const = default;
};

class Viewport
{
public:
    static Result<Viewport> create(const ViewportSpec &spec);

    // NDC (x right, y up, [-1,1]^2 on the window) -> frame pixel in the origin's convention.
    glm::dvec2 ndcToPixel(const glm::dvec2 &ndc) const { return ndc * scale_ + offset_; }
    glm::dvec2 pixelToNdc(const glm::dvec2 &pixel) const { return (pixel - offset_) / scale_; }
    // A pixel in the origin's convention -> the same pixel counted from the top-left (memory order), and back (the
    // same mirror). The camera and everything after it count pixels in memory order; these are the edges where a
    // user's pixels come in (screen positions in the config) or go out (`overlayd project`).
    glm::dvec2 toTopLeft(const glm::dvec2 &pixel) const;
    glm::dvec2 toUser(const glm::dvec2 &memoryPixel) const { return toTopLeft(memoryPixel); }
    // An offset given in the origin's convention (y up under BottomLeft) as a memory-order offset.
    glm::dvec2 offsetToTopLeft(const glm::dvec2 &offset) const;
    bool inScissor(const glm::dvec2 &pixel) const;
    bool inWindow(const glm::dvec2 &pixel) const;

    const PixelRect &window() const { return window_; }
    const PixelRect &scissor() const { return scissor_; }
    // The scissor rectangle counted from the top-left, for rasterizers that address memory.
    PixelRect scissorTopLeft() const;
    Origin origin() const { return spec_.origin; }
    int frameWidth() const { return spec_.frameWidth; }
    int frameHeight() const { return spec_.frameHeight; }
    // Width / height of the window in physical units: the aspect a projection needs for round circles.
    double windowAspect() const;

private:
    explicit Viewport(const ViewportSpec &spec);

    ViewportSpec spec_;
    PixelRect window_;
    PixelRect scissor_;
    glm::dvec2 scale_{0.0};
    glm::dvec2 offset_{0.0};
};

} // namespace overlayd
