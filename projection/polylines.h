// SPDX-License-Identifier: Apache-2.0
// A flat list of 2D polylines: one point array plus where each polyline ends (no allocation per polyline).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace overlayd {

struct Polylines {
    std::vector<glm::dvec2> points;
    std::vector<std::size_t> ends; // ends[i] is one past the last point of polyline i

    std::size_t size() const { return ends.size(); }
    std::span<const glm::dvec2> operator[](std::size_t i) const
    {
        const std::size_t begin = i == 0 ? 0 : ends[i - 1];
        return {points.data() + begin, ends[i] - begin};
    }
    void clear()
    {
        points.clear();
        ends.clear();
    }
    // Starts a new polyline at p.
    void start(const glm::dvec2 &p)
    {
        points.push_back(p);
        ends.push_back(points.size());
    }
    // Extends the last polyline to p.
    void extend(const glm::dvec2 &p)
    {
        points.push_back(p);
        ends.back() = points.size();
    }
};

} // namespace overlayd
