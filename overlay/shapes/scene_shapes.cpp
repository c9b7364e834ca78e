// SPDX-License-Identifier: Apache-2.0
// Builders for shapes derived from scene geometry: the horizon, vehicle guide lines and another camera's frustum.
#include "overlay/shapes/shape_context.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "overlay/shapes/guide_lines.h"

namespace overlayd {

namespace {

// A distance between the camera's near and far planes (their geometric mean), from the projection's depth rows;
// infinity when there is no far plane.
double horizonDistance(const Projection &projection)
{
    if (!projection.hasFarPlane())
        return kInfiniteFar;
    // NDC depth of a point at distance z in front: depth(z) = -A + B / z, with A = m[2][2], B = m[3][2].
    const glm::dmat4 &m = projection.matrix();
    const double near = m[3][2] / (ndcNearDepth(projection.depthRange()) + m[2][2]);
    const double far = m[3][2] / (1.0 + m[2][2]);
    return std::sqrt(near * far);
}

glm::dvec3 anyPerpendicular(const glm::dvec3 &n)
{
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(n, helper));
}

} // namespace

// The horizon of a plane is the image of its directions at infinity. A point at the camera centre plus any
// distance along a direction lands on that direction's vanishing point, so the circle of plane directions around
// the camera centre projects exactly onto the horizon; without a far plane the directions themselves (w = 0) do.
void buildHorizon(const ShapeContext &ctx, const HorizonShape &shape)
{
    if (!ctx.camera.projection().isPerspective() || glm::length(shape.normal) == 0.0)
        return; // an orthographic view has no horizon
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(ctx.worldFromFrame)));
    const glm::dvec3 n = glm::normalize(normalMatrix * shape.normal);
    const glm::dvec3 u = anyPerpendicular(n), v = glm::cross(n, u);
    const double distance = horizonDistance(ctx.camera.projection());
    const glm::dvec3 centre = ctx.camera.position();
    std::vector<glm::dvec4> circle;
    constexpr int kPoints = 96;
    for (int i = 0; i < kPoints; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / kPoints;
        const glm::dvec3 direction = std::cos(angle) * u + std::sin(angle) * v;
        circle.push_back(std::isinf(distance) ? glm::dvec4(direction, 0.0)
                                              : glm::dvec4(centre + distance * direction, 1.0));
    }
    ctx.camera.projectPolyline(circle, true, ctx.stroke().lines);
}

void buildGuideLines(const ShapeContext &ctx, const GuideLinesShape &shape)
{
    if (!shape.steeringKnown) {
        // Unknown must be unmistakable on any ground (grey marks vanish on grey asphalt): each mark is drawn over a
        // black halo kStaleHaloPx wider, so that a light colour shows on a light ground and the halo on a dark one.
        constexpr double kStaleHaloPx = 4.0;
        GuideLinesShape straight = shape;
        straight.steeringDeg = 0.0;
        const auto marks = guideGeometry(straight).marks;
        StrokeItem &halo = ctx.stroke(Rgba{0, 0, 0, 255});
        halo.style.width += kStaleHaloPx;
        for (const auto &mark : marks)
            ctx.segment(halo, mark[0], mark[1]);
        StrokeItem &line = ctx.stroke(shape.staleColour);
        for (const auto &mark : marks)
            ctx.segment(line, mark[0], mark[1]);
        return;
    }
    const GuideGeometry geometry = guideGeometry(shape);
    StrokeItem &wheels = ctx.stroke();
    for (const auto &track : geometry.wheels)
        ctx.polyline(wheels, track, false);
    for (size_t i = 0; i < geometry.marks.size(); ++i) {
        const Rgba colour = i < shape.markColours.size() ? shape.markColours[i] : ctx.style.colour;
        ctx.segment(ctx.stroke(colour), geometry.marks[i][0], geometry.marks[i][1]);
    }
}

// The other camera's near rectangle comes from inverting its projection at the NDC corners; the far rectangle is
// the same rays cut at farDistance (or the same rectangle moved back, for an orthographic projection).
void buildFrustum(const ShapeContext &ctx, const FrustumShape &shape)
{
    const glm::dmat4 inverseProjection = glm::inverse(shape.projection);
    const glm::dmat4 frameFromCamera = glm::inverse(shape.pose.viewMatrix());
    const bool perspective = shape.projection[2][3] != 0.0;
    const double nearDepth = ndcNearDepth(shape.depth);
    std::array<glm::dvec3, 4> nearCorners, farCorners;
    const std::array<glm::dvec2, 4> ndc{glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)};
    for (int i = 0; i < 4; ++i) {
        const glm::dvec4 h = inverseProjection * glm::dvec4(ndc[i], nearDepth, 1.0);
        const glm::dvec3 p = glm::dvec3(h) / h.w;
        const glm::dvec3 far = perspective ? p * (shape.farDistance / -p.z) : glm::dvec3(p.x, p.y, -shape.farDistance);
        nearCorners[i] = glm::dvec3(frameFromCamera * glm::dvec4(p, 1.0));
        farCorners[i] = glm::dvec3(frameFromCamera * glm::dvec4(far, 1.0));
    }
    StrokeItem &item = ctx.stroke();
    ctx.polyline(item, nearCorners, true);
    ctx.polyline(item, farCorners, true);
    const glm::dvec3 apex = shape.pose.position();
    for (int i = 0; i < 4; ++i) {
        ctx.segment(item, nearCorners[i], farCorners[i]);
        if (perspective)
            ctx.segment(item, apex, nearCorners[i]);
    }
}

} // namespace overlayd
