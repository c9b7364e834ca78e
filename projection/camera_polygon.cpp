// SPDX-License-Identifier: Apache-2.0
// Camera::projectPolygon: a filled world polygon (a privacy mask) clipped in clip space, so that a polygon reaching
// behind the camera keeps the part in front instead of folding its hidden corners onto the image.
#include "projection/camera.h"

namespace overlayd {

Status Camera::projectPolygon(std::span<const glm::dvec4> world, std::vector<glm::dvec2> &out, double tolerancePx) const
{
    out.clear();
    if (path_.wide)
        return makeError(ErrorCode::InvalidArgument,
                         "a world polygon cannot be projected through a lens that sees behind the camera");
    std::vector<glm::dvec4> clip, clipped;
    clip.reserve(world.size());
    for (const glm::dvec4 &p : world)
        clip.push_back(viewProjection_ * p);
    segmentPlanes_.clipPolygon(clip, clipped);
    Polylines outline;
    for (size_t i = 0; i < clipped.size(); ++i) {
        const glm::dvec4 &a = clipped[i], &b = clipped[(i + 1) % clipped.size()];
        emitPiece(a, b - a, 0.0, 1.0, true, tolerancePx, outline);
    }
    out = std::move(outline.points);
    return Ok{};
}

} // namespace overlayd
