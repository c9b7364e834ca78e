// SPDX-License-Identifier: Apache-2.0
// Viewport validation and the affine NDC <-> pixel mapping for both origins.
#include "viewport.h"

#include <cmath>
#include <string>

namespace overlayd {

bool PixelRect::contains(const PixelRect &inner) const
{
    return inner.x >= x && inner.y >= y && inner.x + inner.width <= x + width && inner.y + inner.height <= y + height;
}

namespace {

std::string describe(const PixelRect &r)
{
    return std::to_string(r.width) + "x" + std::to_string(r.height) + " at (" + std::to_string(r.x) + ", " +
           std::to_string(r.y) + ")";
}

Status validate(const ViewportSpec &spec)
{
    if (spec.frameWidth <= 0 || spec.frameHeight <= 0)
        return makeError(ErrorCode::InvalidArgument, "viewport frame size must be positive (got " +
                                                         std::to_string(spec.frameWidth) + "x" +
                                                         std::to_string(spec.frameHeight) + ")");
    const PixelRect frame{0, 0, spec.frameWidth, spec.frameHeight};
    if (spec.window) {
        if (spec.window->width <= 0 || spec.window->height <= 0)
            return makeError(ErrorCode::InvalidArgument, "viewport window is empty: " + describe(*spec.window));
        if (!frame.contains(*spec.window))
            return makeError(ErrorCode::InvalidArgument,
                             "viewport window " + describe(*spec.window) + " does not fit the frame");
    }
    if (spec.scissor && (spec.scissor->width < 0 || spec.scissor->height < 0 || !frame.contains(*spec.scissor)))
        return makeError(ErrorCode::InvalidArgument,
                         "scissor " + describe(*spec.scissor) + " is not a rectangle inside the frame");
    if (!std::isfinite(spec.pixelAspect) || spec.pixelAspect <= 0.0)
        return makeError(ErrorCode::InvalidArgument, "pixel aspect must be > 0");
    return Ok{};
}

} // namespace

Result<Viewport> Viewport::create(const ViewportSpec &spec)
{
    if (auto status = validate(spec); !status)
        return status.error();
    return Viewport(spec);
}

Viewport::Viewport(const ViewportSpec &spec) : spec_(spec)
{
    window_ = spec.window.value_or(PixelRect{0, 0, spec.frameWidth, spec.frameHeight});
    scissor_ = spec.scissor.value_or(window_);
    // NDC -1 is the outer edge of the window's first pixel (-0.5 from its centre), +1 the outer edge of its last.
    const double sx = window_.width / 2.0, sy = window_.height / 2.0;
    const bool topLeft = spec.origin == Origin::TopLeft;
    scale_ = {sx, topLeft ? -sy : sy};
    offset_ = {window_.x + sx - 0.5, window_.y + sy - 0.5};
}

glm::dvec2 Viewport::toTopLeft(const glm::dvec2 &pixel) const
{
    if (spec_.origin == Origin::TopLeft)
        return pixel;
    return {pixel.x, spec_.frameHeight - 1.0 - pixel.y};
}

glm::dvec2 Viewport::offsetToTopLeft(const glm::dvec2 &offset) const
{
    return spec_.origin == Origin::TopLeft ? offset : glm::dvec2(offset.x, -offset.y);
}

bool Viewport::inScissor(const glm::dvec2 &p) const
{
    return p.x >= scissor_.x - 0.5 && p.x <= scissor_.x + scissor_.width - 0.5 && p.y >= scissor_.y - 0.5 &&
           p.y <= scissor_.y + scissor_.height - 0.5;
}

bool Viewport::inWindow(const glm::dvec2 &p) const
{
    return p.x >= window_.x - 0.5 && p.x <= window_.x + window_.width - 0.5 && p.y >= window_.y - 0.5 &&
           p.y <= window_.y + window_.height - 0.5;
}

PixelRect Viewport::scissorTopLeft() const
{
    if (spec_.origin == Origin::TopLeft)
        return scissor_;
    return {scissor_.x, spec_.frameHeight - scissor_.y - scissor_.height, scissor_.width, scissor_.height};
}

double Viewport::windowAspect() const
{
    return window_.width * spec_.pixelAspect / window_.height;
}

} // namespace overlayd
