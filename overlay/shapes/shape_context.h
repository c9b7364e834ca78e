// SPDX-License-Identifier: Apache-2.0
// The state every shape builder shares, and the per-shape builders that turn an annotation into 2D primitives.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "overlay/shapes/annotation.h"
#include "overlay/shapes/primitives.h"
#include "projection/camera.h"

namespace overlayd {

struct ShapeContext {
    const Camera &camera;
    glm::dmat4 worldFromFrame; // the annotation's scene-graph frame
    const Style &style;
    DrawList &out;

    // A new stroke with the annotation's style in another colour.
    StrokeItem &stroke(Rgba colour) const;
    StrokeItem &stroke() const { return stroke(style.colour); }
    // A 3D segment or polyline in the annotation's frame, projected, clipped and curved through the lens. Every
    // pixel here is in memory order (screen builders convert the user's positions with Viewport::toTopLeft).
    void segment(StrokeItem &item, const glm::dvec3 &a, const glm::dvec3 &b) const;
    void polyline(StrokeItem &item, std::span<const glm::dvec3> points, bool closed) const;
    // The pixel of a 3D point in the frame, or nothing when it is clipped (behind the camera, beyond far, ...).
    std::optional<glm::dvec2> point(const glm::dvec3 &p) const;
    // A 2D polyline in memory-order pixels.
    void pixels(StrokeItem &item, std::span<const glm::dvec2> points, bool closed) const;
    // Text whose box corner nearest the viewport's origin sits at `corner` (a memory-order pixel).
    void text(const std::string &text, const glm::dvec2 &corner, double sizePx, Rgba colour,
              const std::optional<Rgba> &background, TextAlign align = TextAlign::Left) const;
};

void buildAxes(const ShapeContext &ctx, const AxesShape &shape);
void buildGrid(const ShapeContext &ctx, const GridShape &shape);
void buildPolyline(const ShapeContext &ctx, const PolylineShape &shape);
void buildMarkers(const ShapeContext &ctx, const MarkersShape &shape);
void buildBox(const ShapeContext &ctx, const BoxShape &shape);
void buildArc(const ShapeContext &ctx, const ArcShape &shape);
void buildLabel(const ShapeContext &ctx, const LabelShape &shape);
void buildHorizon(const ShapeContext &ctx, const HorizonShape &shape);
void buildGuideLines(const ShapeContext &ctx, const GuideLinesShape &shape);
void buildFrustum(const ShapeContext &ctx, const FrustumShape &shape);
void buildScreenText(const ShapeContext &ctx, const ScreenTextShape &shape);
void buildCrosshair(const ShapeContext &ctx, const CrosshairShape &shape);
void buildRect(const ShapeContext &ctx, const RectShape &shape);

} // namespace overlayd
