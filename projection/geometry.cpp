// SPDX-License-Identifier: Apache-2.0
// The homogeneous line, ray and plane geometry.
#include "geometry.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>

namespace overlayd {

Plane Plane::fromPointNormal(const glm::dvec3 &point, const glm::dvec3 &normal)
{
    const glm::dvec3 n = glm::normalize(normal);
    return {n, -glm::dot(n, point)};
}

std::optional<Plane> Plane::fromPoints(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
{
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    if (length <= 1e-12 * glm::length(b - a) * glm::length(c - a) || length == 0.0)
        return std::nullopt;
    return fromPointNormal(a, n / length);
}

std::optional<double> intersect(const Ray &ray, const Plane &plane)
{
    const double lv = glm::dot(plane.homogeneous(), glm::dvec4(ray.direction, 0.0));
    if (std::abs(lv) < 1e-15)
        return std::nullopt;
    const double t = -glm::dot(plane.homogeneous(), glm::dvec4(ray.origin, 1.0)) / lv;
    if (t < 0.0)
        return std::nullopt;
    return t;
}

std::optional<double> intersectLine(const glm::dvec3 &p0, const glm::dvec3 &p1, const Plane &plane)
{
    const double d0 = plane.signedDistance(p0), d1 = plane.signedDistance(p1);
    if (std::abs(d0 - d1) < 1e-15)
        return std::nullopt;
    return d0 / (d0 - d1);
}

double pointLineDistance(const glm::dvec3 &point, const glm::dvec3 &linePoint, const glm::dvec3 &lineDirection)
{
    const glm::dvec3 u = glm::normalize(lineDirection);
    const glm::dvec3 v = point - linePoint;
    return glm::length(v - glm::dot(v, u) * u);
}

std::array<std::optional<Plane>, 6> frustumPlanes(const glm::dmat4 &m, DepthRange depth)
{
    const glm::dvec4 r0 = glm::row(m, 0), r1 = glm::row(m, 1), r2 = glm::row(m, 2), r3 = glm::row(m, 3);
    const std::array<glm::dvec4, 6> raw = {
        r3 + r0, r3 - r0, r3 + r1, r3 - r1, depth == DepthRange::ZeroToOne ? r2 : r3 + r2, r3 - r2};
    std::array<std::optional<Plane>, 6> planes;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const double length = glm::length(glm::dvec3(raw[i]));
        if (length > 1e-12 * std::max(1.0, std::abs(raw[i].w)))
            planes[i] = Plane{glm::dvec3(raw[i]) / length, raw[i].w / length};
    }
    return planes;
}

} // namespace overlayd
