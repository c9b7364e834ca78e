// SPDX-License-Identifier: Apache-2.0
// Builders for screen-space items: positions given in the viewport's origin convention (the user's), converted to
// memory order here, no projection.
#include "overlay/shapes/shape_context.h"

#include <array>

#include <glm/common.hpp>

namespace overlayd {

void buildScreenText(const ShapeContext &ctx, const ScreenTextShape &shape)
{
    ctx.text(shape.text, ctx.camera.viewport().toTopLeft(shape.position), shape.sizePx, ctx.style.colour,
             shape.background, shape.align);
}

void buildCrosshair(const ShapeContext &ctx, const CrosshairShape &shape)
{
    const Viewport &viewport = ctx.camera.viewport();
    const PixelRect &window = viewport.window();
    // The window's centre (the window is given in the user's origin): pixel centres run from x to x + width - 1.
    const glm::dvec2 centre = viewport.toTopLeft(
        shape.position.value_or(glm::dvec2(window.x + (window.width - 1) / 2.0, window.y + (window.height - 1) / 2.0)));
    const double half = 0.5 * shape.sizePx;
    StrokeItem &item = ctx.stroke();
    const std::array<glm::dvec2, 2> horizontal{centre - glm::dvec2(half, 0), centre + glm::dvec2(half, 0)};
    const std::array<glm::dvec2, 2> vertical{centre - glm::dvec2(0, half), centre + glm::dvec2(0, half)};
    ctx.pixels(item, horizontal, false);
    ctx.pixels(item, vertical, false);
}

void buildRect(const ShapeContext &ctx, const RectShape &shape)
{
    // The rectangle covers pixels position .. position + size - 1: its outline runs through their outer edges.
    const Viewport &viewport = ctx.camera.viewport();
    const glm::dvec2 a = shape.position - glm::dvec2(0.5), b = shape.position + shape.size - glm::dvec2(0.5);
    const std::array<glm::dvec2, 4> corners{viewport.toTopLeft(a), viewport.toTopLeft(glm::dvec2(b.x, a.y)),
                                            viewport.toTopLeft(b), viewport.toTopLeft(glm::dvec2(a.x, b.y))};
    if (!shape.filled) {
        ctx.pixels(ctx.stroke(), corners, true);
        return;
    }
    // Whole pixels: the first and last pixel of the rectangle, each converted to memory order.
    const glm::dvec2 first = viewport.toTopLeft(glm::round(shape.position));
    const glm::dvec2 last = viewport.toTopLeft(glm::round(shape.position + shape.size) - glm::dvec2(1.0));
    const glm::dvec2 low = glm::min(first, last), high = glm::max(first, last);
    ctx.out.fills.push_back({ctx.style.colour, int(low.x), int(low.y), int(high.x) + 1, int(high.y) + 1});
}

} // namespace overlayd
