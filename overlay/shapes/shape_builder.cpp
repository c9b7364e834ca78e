// SPDX-License-Identifier: Apache-2.0
// The dispatch from each shape to its builder.
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

} // namespace

void buildPrimitives(const Annotation &annotation, const glm::dmat4 &worldFromFrame, const Camera &camera,
                     DrawList &out)
{
    const ShapeContext ctx{camera, worldFromFrame, annotation.style, out};
    std::visit(Overloaded{
                   [&](const AxesShape &s) { buildAxes(ctx, s); }, [&](const GridShape &s) { buildGrid(ctx, s); },
                   [&](const PolylineShape &s) { buildPolyline(ctx, s); },
                   [&](const MarkersShape &s) { buildMarkers(ctx, s); }, [&](const BoxShape &s) { buildBox(ctx, s); },
                   [&](const ArcShape &s) { buildArc(ctx, s); }, [&](const LabelShape &s) { buildLabel(ctx, s); },
                   [&](const HorizonShape &s) { buildHorizon(ctx, s); },
                   [&](const GuideLinesShape &s) { buildGuideLines(ctx, s); },
                   [&](const FrustumShape &s) { buildFrustum(ctx, s); },
                   [&](const ScreenTextShape &s) { buildScreenText(ctx, s); },
                   [&](const CrosshairShape &s) { buildCrosshair(ctx, s); },
                   [&](const RectShape &s) { buildRect(ctx, s); },
                   [&](const ImageShape &) {}, // pixels, not primitives: SceneRenderer warps them (image_quad.h)
                   [&](const MaskShape &) {},  // burned into the frame, not drawn over it (privacy_masks.h)
               },
               annotation.shape);
}

bool isScreenText(const Annotation &annotation)
{
    return std::holds_alternative<ScreenTextShape>(annotation.shape);
}

} // namespace overlayd
