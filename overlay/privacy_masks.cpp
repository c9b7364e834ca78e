// SPDX-License-Identifier: Apache-2.0
// PrivacyMasks: each mask's polygon to pixel spans on camera changes, filled or pixelated per frame.
#include "overlay/privacy_masks.h"

namespace overlayd {

PrivacyMasks::PrivacyMasks(const OverlayScene &scene, const StreamFormat &format)
    : width_(format.width), height_(format.height),
      painter_(*format.format, format.colorimetry, format.width, format.height)
{
    for (const Annotation &annotation : scene.annotations)
        if (const auto *mask = std::get_if<MaskShape>(&annotation.shape))
            masks_.push_back({annotation.name, annotation.frame, *mask, {}});
}

Result<SpanRows> PrivacyMasks::rasterize(const Mask &mask, const Camera &camera, const SceneGraph &graph) const
{
    // polygonSpans puts pixel (x, y)'s centre at (x + 0.5, y + 0.5); the camera puts it at (x, y).
    std::vector<glm::dvec2> outline;
    if (mask.shape.world) {
        const Result<glm::dmat4> worldFromFrame = graph.worldMatrix(mask.frame);
        if (!worldFromFrame)
            return worldFromFrame.error();
        std::vector<glm::dvec4> world;
        for (const glm::dvec3 &p : mask.shape.points)
            world.push_back(*worldFromFrame * glm::dvec4(p, 1.0));
        if (Status projected = camera.projectPolygon(world, outline); !projected)
            return projected.error();
        for (glm::dvec2 &p : outline)
            p += glm::dvec2(0.5);
    } else {
        // Screen points are pixel corners in the viewport's origin: [x, y] is the corner of pixel (x, y) nearest the
        // origin, (x - 0.5, y - 0.5) in the centred convention, so [0, 0] .. [w, h] covers w x h pixels either way.
        for (const glm::dvec3 &p : mask.shape.points)
            outline.push_back(camera.viewport().toTopLeft(glm::dvec2(p) - glm::dvec2(0.5)) + glm::dvec2(0.5));
    }
    std::vector<RowSpan> spans;
    polygonSpans(outline, int(width_), int(height_), spans);
    return SpanRows(std::move(spans), width_, height_, painter_.hSub(), painter_.vSub());
}

Status PrivacyMasks::setCamera(const Camera &camera, const SceneGraph &graph)
{
    std::vector<SpanRows> rows;
    for (const Mask &mask : masks_) {
        Result<SpanRows> spans = rasterize(mask, camera, graph);
        if (!spans)
            return makeError(spans.error().code, "mask \"" + mask.name + "\": " + spans.error().message);
        rows.push_back(std::move(*spans));
    }
    for (size_t i = 0; i < masks_.size(); ++i)
        masks_[i].rows = std::move(rows[i]);
    return Ok{};
}

void PrivacyMasks::apply(const FrameView &frame)
{
    for (const Mask &mask : masks_) {
        if (mask.shape.fill)
            painter_.fill(frame, mask.rows, *mask.shape.fill);
        else
            painter_.pixelate(frame, mask.rows, mask.shape.blockPx);
    }
}

} // namespace overlayd
