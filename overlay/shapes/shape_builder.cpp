// The dispatch from each shape to its builder, and the final step into memory order.
#include "overlay/shapes/shape_builder.h"

#include <type_traits>

#include "overlay/shapes/shape_context.h"

namespace overlayd {

namespace {

template<typename... Ts>
struct Overloaded : Ts... {
    using Ts::operator()...;
};
template<typename... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// Builders work in the viewport's origin convention (the one users and projection/ speak); the rasterizer
// addresses memory. Text anchors and fills were converted when they were made.
void toMemoryOrder(const Viewport &viewport, DrawList &out, size_t firstStroke)
{
    for (size_t i = firstStroke; i < out.strokes.size(); ++i) {
        for (glm::dvec2 &p : out.strokes[i].lines.points)
            p = viewport.toTopLeft(p);
    }
}

} // namespace

void buildPrimitives(const Annotation &annotation, const glm::dmat4 &worldFromFrame, const Camera &camera,
                     DrawList &out)
{
    const size_t firstStroke = out.strokes.size();
    const ShapeContext ctx{camera, worldFromFrame, annotation.style, out};
    std::visit(Overloaded{
                   [&](const AxesShape &s) { buildAxes(ctx, s); },
                   [&](const GridShape &s) { buildGrid(ctx, s); },
                   [&](const PolylineShape &s) { buildPolyline(ctx, s); },
                   [&](const MarkersShape &s) { buildMarkers(ctx, s); },
                   [&](const BoxShape &s) { buildBox(ctx, s); },
                   [&](const ArcShape &s) { buildArc(ctx, s); },
                   [&](const LabelShape &s) { buildLabel(ctx, s); },
                   [&](const HorizonShape &s) { buildHorizon(ctx, s); },
                   [&](const GuideLinesShape &s) { buildGuideLines(ctx, s); },
                   [&](const FrustumShape &s) { buildFrustum(ctx, s); },
                   [&](const ScreenTextShape &s) { buildScreenText(ctx, s); },
                   [&](const CrosshairShape &s) { buildCrosshair(ctx, s); },
                   [&](const RectShape &s) { buildRect(ctx, s); },
               },
               annotation.shape);
    toMemoryOrder(camera.viewport(), out, firstStroke);
}

bool isScreenText(const Annotation &annotation)
{
    return std::holds_alternative<ScreenTextShape>(annotation.shape);
}

} // namespace overlayd
