// SPDX-License-Identifier: Apache-2.0
// ShapeContext: projection of an annotation's geometry through the camera into stroke and text primitives.
#include "overlay/shapes/shape_context.h"

#include <vector>

namespace overlayd {

StrokeItem &ShapeContext::stroke(Rgba colour) const
{
    out.strokes.push_back({StrokeStyle{colour, style.width, style.dash, style.antialias}, Polylines{}});
    return out.strokes.back();
}

void ShapeContext::segment(StrokeItem &item, const glm::dvec3 &a, const glm::dvec3 &b) const
{
    camera.projectSegment(worldFromFrame * glm::dvec4(a, 1.0), worldFromFrame * glm::dvec4(b, 1.0), item.lines);
}

void ShapeContext::polyline(StrokeItem &item, std::span<const glm::dvec3> points, bool closed) const
{
    std::vector<glm::dvec4> world;
    world.reserve(points.size());
    for (const glm::dvec3 &p : points)
        world.push_back(worldFromFrame * glm::dvec4(p, 1.0));
    camera.projectPolyline(world, closed, item.lines);
}

std::optional<glm::dvec2> ShapeContext::point(const glm::dvec3 &p) const
{
    const ProjectedPoint projected = camera.project(worldFromFrame * glm::dvec4(p, 1.0));
    if (projected.status == PointStatus::Clipped)
        return std::nullopt;
    return projected.pixel;
}

void ShapeContext::pixels(StrokeItem &item, std::span<const glm::dvec2> points, bool closed) const
{
    if (points.empty())
        return;
    item.lines.start(points[0]);
    for (size_t i = 1; i < points.size(); ++i)
        item.lines.extend(points[i]);
    if (closed)
        item.lines.extend(points[0]);
}

void ShapeContext::text(const std::string &string, const glm::dvec2 &corner, double sizePx, Rgba colour,
                        const std::optional<Rgba> &background, TextAlign align) const
{
    const Viewport &viewport = camera.viewport();
    out.texts.push_back(TextItem{string, corner, viewport.origin() == Origin::BottomLeft, sizePx, colour, background,
                                 style.antialias, align});
}

} // namespace overlayd
