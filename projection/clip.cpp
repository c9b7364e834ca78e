// SPDX-License-Identifier: Apache-2.0
// Liang-Barsky and Sutherland-Hodgman clipping in homogeneous coordinates.
#include "clip.h"

#include <glm/geometric.hpp>

namespace overlayd {

ClipPlanes::ClipPlanes(DepthRange depth, bool far, const NdcBounds &s)
{
    // x >= xMin w  <=>  dot((1, 0, 0, -xMin), c) >= 0, and so on.
    planes_[count_++] = depth == DepthRange::ZeroToOne ? glm::dvec4(0, 0, 1, 0) : glm::dvec4(0, 0, 1, 1);
    if (far)
        planes_[count_++] = glm::dvec4(0, 0, -1, 1);
    planes_[count_++] = glm::dvec4(1, 0, 0, -s.xMin);
    planes_[count_++] = glm::dvec4(-1, 0, 0, s.xMax);
    planes_[count_++] = glm::dvec4(0, 1, 0, -s.yMin);
    planes_[count_++] = glm::dvec4(0, -1, 0, s.yMax);
}

bool ClipPlanes::inside(const glm::dvec4 &clip) const
{
    if (!(clip.w > 0.0))
        return false;
    for (const glm::dvec4 &plane : planes())
        if (glm::dot(plane, clip) < 0.0)
            return false;
    return true;
}

std::optional<std::array<double, 2>> ClipPlanes::clipSegment(const glm::dvec4 &a, const glm::dvec4 &b) const
{
    double t0 = 0.0, t1 = 1.0;
    for (const glm::dvec4 &plane : planes()) {
        const double da = glm::dot(plane, a), db = glm::dot(plane, b);
        if (da < 0.0 && db < 0.0)
            return std::nullopt;
        if (da < 0.0)
            t0 = std::max(t0, da / (da - db));
        else if (db < 0.0)
            t1 = std::min(t1, da / (da - db));
    }
    if (t0 > t1)
        return std::nullopt;
    return std::array<double, 2>{t0, t1};
}

void ClipPlanes::clipPolygon(std::span<const glm::dvec4> polygon, std::vector<glm::dvec4> &out) const
{
    out.assign(polygon.begin(), polygon.end());
    std::vector<glm::dvec4> input;
    for (const glm::dvec4 &plane : planes()) {
        if (out.empty())
            return;
        input.swap(out);
        out.clear();
        for (std::size_t i = 0; i < input.size(); ++i) {
            const glm::dvec4 &current = input[i];
            const glm::dvec4 &next = input[(i + 1) % input.size()];
            const double dc = glm::dot(plane, current), dn = glm::dot(plane, next);
            if (dc >= 0.0)
                out.push_back(current);
            if ((dc >= 0.0) != (dn >= 0.0))
                out.push_back(current + (next - current) * (dc / (dc - dn)));
        }
    }
}

} // namespace overlayd
