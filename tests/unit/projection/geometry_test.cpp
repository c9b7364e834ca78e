// SPDX-License-Identifier: Apache-2.0
// geometry_test: the homogeneous form's lines, rays, planes, distances, intersections and the view frustum's six
// planes.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "projection/geometry.h"
#include "projection/pose.h"
#include "projection/projection.h"

using namespace overlayd;

namespace {

class Geometry : public ::testing::Test
{
protected:
    glm::dvec3 vec(double lo, double hi)
    {
        std::uniform_real_distribution<double> u(lo, hi);
        return {u(rng_), u(rng_), u(rng_)};
    }
    std::mt19937_64 rng_{31};
};

TEST_F(Geometry, LinePlaneIntersectionUsesTheCorrectedParametricLine)
{
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 p1 = vec(-5, 5), p2 = vec(-5, 5);
        const Plane plane = Plane::fromPointNormal(vec(-2, 2), vec(-1, 1));
        // The homogeneous form t = -(L.S)/(L.V), with S = (P1, 1) and V = (P2 - P1, 0).
        const glm::dvec4 l(plane.normal, plane.d);
        const double lv = glm::dot(l, glm::dvec4(p2 - p1, 0.0));
        if (std::abs(lv) < 1e-3)
            continue;
        const double expected = -glm::dot(l, glm::dvec4(p1, 1.0)) / lv;
        auto t = intersectLine(p1, p2, plane);
        ASSERT_TRUE(t.has_value());
        EXPECT_NEAR(*t, expected, 1e-9 * std::max(1.0, std::abs(expected)));
        // P(t) = (1 - t) P1 + t P2 lies on the plane. The derivation prints (1 - t) P1 + P2, which drops the t on P2
        // (at t = 0 it gives P1 + P2, not P1).
        const glm::dvec3 hit = (1.0 - *t) * p1 + *t * p2;
        EXPECT_NEAR(plane.signedDistance(hit), 0.0, 1e-9 * std::max(1.0, std::abs(*t)));
    }
    // A line parallel to the plane meets it nowhere.
    EXPECT_FALSE(intersectLine({0, 0, 1}, {1, 2, 1}, Plane::fromPointNormal({0, 0, 0}, {0, 0, 1})).has_value());
    // Unlike a ray, the line's parameter may be negative or beyond 1.
    auto before = intersectLine({0, 0, 1}, {0, 0, 2}, Plane::fromPointNormal({0, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(before.has_value());
    EXPECT_NEAR(*before, -1.0, 1e-15);
}

TEST_F(Geometry, RayPlaneIntersection)
{
    const Plane ground = Plane::fromPointNormal({0, 0, 0}, {0, 0, 1});
    auto t = intersect(Ray{{1, 2, 5}, {0, 0, -1}}, ground);
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 5.0, 1e-15);
    const Ray slanted{{0, 0, 3}, glm::normalize(glm::dvec3(1, 0, -1))};
    auto s = intersect(slanted, ground);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(slanted.at(*s).x, 3.0, 1e-12);
    EXPECT_NEAR(slanted.at(*s).z, 0.0, 1e-12);
    // Behind the origin and parallel rays have no hit.
    EXPECT_FALSE(intersect(Ray{{0, 0, 5}, {0, 0, 1}}, ground).has_value());
    EXPECT_FALSE(intersect(Ray{{0, 0, 5}, {1, 0, 0}}, ground).has_value());
    for (int i = 0; i < 100; ++i) {
        const Ray ray{vec(-5, 5), glm::normalize(vec(-1, 1))};
        const Plane plane = Plane::fromPointNormal(vec(-2, 2), vec(-1, 1));
        // The derivation's t = -(N.S + D) / (N.V).
        const double expected = -(glm::dot(plane.normal, ray.origin) + plane.d) / glm::dot(plane.normal, ray.direction);
        auto hit = intersect(ray, plane);
        if (expected < 0.0 || std::abs(glm::dot(plane.normal, ray.direction)) < 1e-3) {
            EXPECT_EQ(hit.has_value(), expected >= 0.0 && std::isfinite(expected));
            continue;
        }
        ASSERT_TRUE(hit.has_value());
        EXPECT_NEAR(*hit, expected, 1e-9 * std::max(1.0, expected));
        EXPECT_NEAR(plane.signedDistance(ray.at(*hit)), 0.0, 1e-9 * std::max(1.0, expected));
    }
}

TEST_F(Geometry, SignedDistancesArePositiveOnTheNormalsSide)
{
    // A non-unit normal is normalized: distances are in length units.
    const Plane plane = Plane::fromPointNormal({0, 0, 2}, {0, 0, 2});
    EXPECT_NEAR(plane.signedDistance({1, 1, 5}), 3.0, 1e-15);
    EXPECT_NEAR(plane.signedDistance({0, 0, 0}), -2.0, 1e-15);
    EXPECT_NEAR(plane.d, -2.0, 1e-15);
    const Plane tilted = Plane::fromPointNormal({1, 0, 0}, {1, 1, 0});
    EXPECT_NEAR(tilted.signedDistance({0, 1, 7}), 0.0, 1e-15);
    EXPECT_NEAR(tilted.signedDistance({2, 1, 0}), std::sqrt(2.0), 1e-15);

    // Three points, counter-clockwise seen from +Z: normal +Z.
    auto fromPoints = Plane::fromPoints({0, 0, 1}, {1, 0, 1}, {0, 1, 1});
    ASSERT_TRUE(fromPoints.has_value());
    EXPECT_NEAR(fromPoints->normal.z, 1.0, 1e-15);
    EXPECT_NEAR(fromPoints->signedDistance({5, -3, 4}), 3.0, 1e-15);
    EXPECT_FALSE(Plane::fromPoints({0, 0, 0}, {1, 1, 1}, {2, 2, 2}).has_value());
    EXPECT_FALSE(Plane::fromPoints({1, 2, 3}, {1, 2, 3}, {0, 1, 0}).has_value());
}

TEST_F(Geometry, PointLineDistanceMatchesTheHomogeneousForm)
{
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 q = vec(-10, 10), s = vec(-10, 10), v = vec(-3, 3);
        if (glm::length(v) < 0.1)
            continue;
        // d = sqrt(|Q - S|^2 - ((Q - S).V)^2 / V^2), with V of any length.
        const glm::dvec3 qs = q - s;
        const double expected =
            std::sqrt(std::max(0.0, glm::dot(qs, qs) - std::pow(glm::dot(qs, v), 2) / glm::dot(v, v)));
        EXPECT_NEAR(pointLineDistance(q, s, v), expected, 1e-9);
    }
    EXPECT_NEAR(pointLineDistance({3, 4, 0}, {0, 0, 0}, {0, 0, 7}), 5.0, 1e-15);
    EXPECT_NEAR(pointLineDistance({1, 2, 3}, {1, 2, 3}, {1, 0, 0}), 0.0, 1e-15);
}

// The homogeneous form's planes of a camera with horizontal field of view alpha, aspect a = height / width, near n, far
// f: e = 1 / tan(alpha / 2), left/right <+-e, 0, -1> / sqrt(e^2 + 1), bottom/top <0, +-e, -a> / sqrt(e^2 + a^2), near
// <0, 0, -1, -n>, far <0, 0, 1, f>. The derivation prints sqrt(e^2 + 2) for the left and right normals' z; that would
// not be a unit normal: the correct value is sqrt(e^2 + 1).
TEST_F(Geometry, FrustumPlanesOfAFovCameraMatchTheHomogeneousForm)
{
    const double width = 1280, height = 720;
    for (double alphaDeg : {30.0, 60.0, 90.0, 120.0}) {
        const double alpha = alphaDeg * M_PI / 180.0, n = 0.2, f = 150.0;
        const double e = 1.0 / std::tan(alpha / 2.0), a = height / width;
        const glm::dvec4 expected[6] = {glm::dvec4(e, 0, -1, 0) / std::sqrt(e * e + 1),
                                        glm::dvec4(-e, 0, -1, 0) / std::sqrt(e * e + 1),
                                        glm::dvec4(0, e, -a, 0) / std::sqrt(e * e + a * a),
                                        glm::dvec4(0, -e, -a, 0) / std::sqrt(e * e + a * a),
                                        glm::dvec4(0, 0, -1, -n),
                                        glm::dvec4(0, 0, 1, f)};
        // The derivation's misprint: 1 / sqrt(e^2 + 2) makes the left normal shorter than unit.
        EXPECT_LT(std::hypot(e / std::sqrt(e * e + 1), 1 / std::sqrt(e * e + 2)), 1.0 - 1e-3);
        for (DepthRange depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
            auto projection = Projection::perspective(FovAxis::Horizontal, alphaDeg, width / height, n, f, depth);
            ASSERT_TRUE(projection.ok());
            // With the projection alone, the planes come out in camera coordinates.
            const auto planes = frustumPlanes(projection->matrix(), depth);
            for (int side = 0; side < 6; ++side) {
                ASSERT_TRUE(planes[side].has_value()) << "side " << side;
                const glm::dvec4 actual = planes[side]->homogeneous();
                for (int k = 0; k < 4; ++k)
                    EXPECT_NEAR(actual[k], expected[side][k], 1e-12 * std::max(1.0, std::abs(expected[side][k])))
                        << "fov " << alphaDeg << ", side " << side << ", component " << k;
            }
        }
    }
}

TEST_F(Geometry, FrustumPlanesClassifyPointsLikeTheClipCube)
{
    auto pose = poseLookAt({3, -4, 2}, {0, 0, 0.5}, {0, 0, 1});
    ASSERT_TRUE(pose.ok());
    for (DepthRange depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        auto projection = Projection::frustum({-0.15, 0.05, -0.04, 0.09, 0.1, 20.0}, depth);
        ASSERT_TRUE(projection.ok());
        const glm::dmat4 worldToClip = projection->matrix() * pose->viewMatrix();
        const auto planes = frustumPlanes(worldToClip, depth);
        const double zMin = ndcNearDepth(depth);
        // The viewing pipeline: visible when the divided point lies in the cube (here [-1,1]^2 x [zMin, 1]).
        int inside = 0, outside = 0;
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 world = vec(-8, 8);
            const glm::dvec4 clip = worldToClip * glm::dvec4(world, 1.0);
            const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
            const bool inCube =
                clip.w > 0 && std::abs(ndc.x) <= 1 && std::abs(ndc.y) <= 1 && ndc.z >= zMin && ndc.z <= 1;
            bool inPlanes = true;
            double closest = INFINITY;
            for (const auto &plane : planes) {
                const double distance = plane->signedDistance(world);
                inPlanes = inPlanes && distance >= 0.0;
                closest = std::min(closest, std::abs(distance));
            }
            if (closest < 1e-9)
                continue; // on a boundary: either answer is right
            EXPECT_EQ(inPlanes, inCube) << world.x << ", " << world.y << ", " << world.z;
            (inCube ? inside : outside)++;
        }
        EXPECT_GT(inside, 10);
        EXPECT_GT(outside, 10);

        // Hand-picked: on the optical axis between near and far is inside; behind the eye and past far are not.
        const glm::dvec3 eye = pose->position(), forward = glm::normalize(glm::dvec3(0, 0, 0.5) - eye);
        const auto allInside = [&](const glm::dvec3 &p) {
            for (const auto &plane : planes)
                if (plane->signedDistance(p) < 0.0)
                    return false;
            return true;
        };
        // The window is off-axis (l = -0.15, r = 0.05 at near 0.1): aim through its centre instead.
        const glm::dvec3 centreRay = glm::transpose(pose->rotation) * glm::normalize(glm::dvec3(-0.5, 0.25, -1.0));
        EXPECT_TRUE(allInside(eye + 5.0 * centreRay));
        EXPECT_FALSE(allInside(eye + 0.05 * centreRay));
        EXPECT_FALSE(allInside(eye + 25.0 * centreRay));
        EXPECT_FALSE(allInside(eye - 5.0 * forward));
    }
}

TEST_F(Geometry, InfiniteFarHasNoFarPlane)
{
    for (DepthRange depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        auto projection = Projection::perspective(FovAxis::Vertical, 50, 1.5, 0.1, kInfiniteFar, depth);
        ASSERT_TRUE(projection.ok());
        const auto planes = frustumPlanes(projection->matrix(), depth);
        EXPECT_FALSE(planes[int(FrustumSide::Far)].has_value());
        ASSERT_TRUE(planes[int(FrustumSide::Near)].has_value());
        EXPECT_NEAR(planes[int(FrustumSide::Near)]->signedDistance({0, 0, -1e9}), 1e9 - 0.1, 1e-3);
    }
}

} // namespace
