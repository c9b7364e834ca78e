// SPDX-License-Identifier: Apache-2.0
#include "overlay/shapes/image_quad.h"

#include <glm/common.hpp>

namespace overlayd {

std::optional<std::array<glm::dvec2, 4>> imageQuad(const ImageShape &shape, const glm::dmat4 &worldFromFrame,
                                                   const Camera &camera)
{
    if (!shape.image)
        return std::nullopt;
    if (shape.position) {
        // The user's pixels position .. position + size - 1, whose outer edges lie half a pixel further out; the
        // image stays upright, so its top-left corner is whichever converted corner is top-left in memory.
        const glm::dvec2 size = shape.sizePx.value_or(glm::dvec2(shape.image->width, shape.image->height));
        const Viewport &viewport = camera.viewport();
        const glm::dvec2 a = viewport.toTopLeft(*shape.position - glm::dvec2(0.5));
        const glm::dvec2 b = viewport.toTopLeft(*shape.position + size - glm::dvec2(0.5));
        const glm::dvec2 low = glm::min(a, b), high = glm::max(a, b);
        return std::array<glm::dvec2, 4>{low, glm::dvec2(high.x, low.y), high, glm::dvec2(low.x, high.y)};
    }
    const glm::dvec3 centre = shape.anchor.value_or(glm::dvec3(0.0));
    const glm::dvec3 u = glm::normalize(shape.axisU) * (0.5 * shape.size.x);
    const glm::dvec3 v = glm::normalize(shape.axisV) * (0.5 * shape.size.y);
    const std::array<glm::dvec3, 4> corners{centre - u + v, centre + u + v, centre + u - v, centre - u - v};
    std::array<glm::dvec2, 4> out;
    for (size_t i = 0; i < 4; ++i) {
        const ProjectedPoint projected = camera.project(worldFromFrame * glm::dvec4(corners[i], 1.0));
        if (projected.status == PointStatus::Clipped)
            return std::nullopt;
        out[i] = projected.pixel;
    }
    return out;
}

} // namespace overlayd
