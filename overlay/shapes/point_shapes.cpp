// SPDX-License-Identifier: Apache-2.0
// Builders for shapes anchored at projected 3D points: markers and labels. Their size is in pixels, so only the
// anchor goes through the projection; a clipped anchor (behind the camera) draws nothing.
#include "overlay/shapes/shape_context.h"

#include <array>
#include <cmath>
#include <numbers>

namespace overlayd {

namespace {

void marker(const ShapeContext &ctx, StrokeItem &item, MarkerKind kind, const glm::dvec2 &c, double half)
{
    switch (kind) {
    case MarkerKind::Cross: {
        const std::array<glm::dvec2, 2> a{c + glm::dvec2(-half, -half), c + glm::dvec2(half, half)};
        const std::array<glm::dvec2, 2> b{c + glm::dvec2(-half, half), c + glm::dvec2(half, -half)};
        ctx.pixels(item, a, false);
        ctx.pixels(item, b, false);
        break;
    }
    case MarkerKind::Plus: {
        const std::array<glm::dvec2, 2> a{c + glm::dvec2(-half, 0), c + glm::dvec2(half, 0)};
        const std::array<glm::dvec2, 2> b{c + glm::dvec2(0, -half), c + glm::dvec2(0, half)};
        ctx.pixels(item, a, false);
        ctx.pixels(item, b, false);
        break;
    }
    case MarkerKind::Square: {
        const std::array<glm::dvec2, 4> square{c + glm::dvec2(-half, -half), c + glm::dvec2(half, -half),
                                               c + glm::dvec2(half, half), c + glm::dvec2(-half, half)};
        ctx.pixels(item, square, true);
        break;
    }
    case MarkerKind::Circle: {
        std::array<glm::dvec2, 32> circle;
        for (size_t i = 0; i < circle.size(); ++i) {
            const double angle = 2.0 * std::numbers::pi * double(i) / double(circle.size());
            circle[i] = c + half * glm::dvec2(std::cos(angle), std::sin(angle));
        }
        ctx.pixels(item, circle, true);
        break;
    }
    }
}

} // namespace

void buildMarkers(const ShapeContext &ctx, const MarkersShape &shape)
{
    StrokeItem &item = ctx.stroke();
    for (const glm::dvec3 &p : shape.points) {
        if (const auto pixel = ctx.point(p))
            marker(ctx, item, shape.kind, *pixel, 0.5 * shape.sizePx);
    }
}

void buildLabel(const ShapeContext &ctx, const LabelShape &shape)
{
    if (const auto pixel = ctx.point(shape.anchor))
        ctx.text(shape.text, *pixel + ctx.camera.viewport().offsetToTopLeft(shape.offsetPx), shape.sizePx,
                 ctx.style.colour, shape.background, shape.align);
}

} // namespace overlayd
