// SPDX-License-Identifier: Apache-2.0
// The homogeneous geometry: rays, planes <N, D>, signed distances, intersections, and the view frustum's planes.
#pragma once

#include <array>
#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "projection.h"

namespace overlayd {

struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0}; // unit length
    glm::dvec3 at(double t) const { return origin + t * direction; }
};

// The plane of points x with dot(normal, x) + d = 0; normal has unit length.
struct Plane {
    glm::dvec3 normal{0.0, 0.0, 1.0};
    double d = 0.0;

    static Plane fromPointNormal(const glm::dvec3 &point, const glm::dvec3 &normal);
    // Normal along (b - a) x (c - a); nothing when the points are collinear.
    static std::optional<Plane> fromPoints(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c);
    // Positive on the side the normal points to.
    double signedDistance(const glm::dvec3 &point) const { return glm::dot(normal, point) + d; }
    glm::dvec4 homogeneous() const { return {normal, d}; }
};

// In homogeneous form t = -(L.S)/(L.V) with L = <N, D>, S = (origin, 1), V = (direction, 0): the ray parameter
// where it meets the plane; nothing when parallel or when the hit is behind the origin (t < 0).
std::optional<double> intersect(const Ray &ray, const Plane &plane);
// The same for the infinite line through p0 and p1, parameter t with P(t) = (1 - t) p0 + t p1 (the derivation drops
// the second t).
std::optional<double> intersectLine(const glm::dvec3 &p0, const glm::dvec3 &p1, const Plane &plane);
double pointLineDistance(const glm::dvec3 &point, const glm::dvec3 &linePoint, const glm::dvec3 &lineDirection);

enum class FrustumSide { Left, Right, Bottom, Top, Near, Far };
// The six planes of the frustum of a world-to-clip matrix, normals pointing inwards (Gribb-Hartmann). For an
// infinite far plane the far plane has a zero normal and is reported as nothing.
std::array<std::optional<Plane>, 6> frustumPlanes(const glm::dmat4 &worldToClip, DepthRange depth);

} // namespace overlayd
