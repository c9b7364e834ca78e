// SPDX-License-Identifier: Apache-2.0
// One ray of the checker scene: from a pixel position through the camera to a square of the ground plane, or the sky.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>

#include "projection/camera.h"

// A namespace of its own: Hit and Square are common names.
namespace overlayd {

// Where one sample's ray meets the ground (x, y in metres), or that it misses it (sky).
struct Hit {
    bool ground = false;
    glm::dvec2 point{0.0};
};

struct Square {
    bool ground = false;
    int64_t i = 0, j = 0;

    bool operator==(const Square &) const = default;
};

class SceneTracer
{
public:
    SceneTracer(const Camera &camera, double squareMetres) : camera_(camera), square_(squareMetres) {}

    // (u, v) in memory order (v counts rows from the top), in the convention where pixel centres are integers.
    Hit trace(double u, double v) const
    {
        const auto ray = camera_.unproject({u, v});
        if (!ray)
            return {};
        const auto t = intersect(*ray, ground_);
        if (!t)
            return {};
        const glm::dvec3 hit = ray->at(*t);
        // Grazing rays meet the ground absurdly far away; past 1e12 squares the index would overflow.
        if (!(std::abs(hit.x) < kFar * square_ && std::abs(hit.y) < kFar * square_))
            return {};
        return {true, {hit.x, hit.y}};
    }

    double squareMetres() const { return square_; }

    Square square(const Hit &hit) const
    {
        if (!hit.ground)
            return {};
        return {true, int64_t(std::floor(hit.point.x / square_)), int64_t(std::floor(hit.point.y / square_))};
    }

private:
    static constexpr double kFar = 1e12;

    const Camera &camera_;
    double square_;
    Plane ground_ = Plane::fromPointNormal({0, 0, 0}, {0, 0, 1});
};

} // namespace overlayd
