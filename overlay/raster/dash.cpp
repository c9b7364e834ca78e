// SPDX-License-Identifier: Apache-2.0
// Walks each polyline by arc length and keeps the pieces that fall in the pattern's "on" intervals.
#include "overlay/raster/dash.h"

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

struct DashState {
    std::span<const double> pattern;
    size_t index = 0;     // the current interval of the pattern (even: on)
    double remaining = 0; // pixels left in it
    bool on() const { return index % 2 == 0; }
    void next()
    {
        index = (index + 1) % pattern.size();
        remaining = lengthOf(index);
    }
    // A negative or nan entry would walk backwards or stall: it counts as 0.
    double lengthOf(size_t i) const { return pattern[i] > 0 ? pattern[i] : 0.0; }
};

void dashPolyline(std::span<const glm::dvec2> line, DashState state, Polylines &out)
{
    if (state.on())
        out.start(line[0]);
    for (size_t i = 1; i < line.size(); ++i) {
        glm::dvec2 from = line[i - 1];
        const glm::dvec2 to = line[i];
        double length = glm::distance(from, to);
        while (length > state.remaining) {
            from += (to - from) * (state.remaining / length);
            length -= state.remaining;
            if (state.on())
                out.extend(from);
            state.next();
            if (state.on())
                out.start(from);
        }
        state.remaining -= length;
        if (state.on())
            out.extend(to);
    }
}

} // namespace

void applyDash(const Polylines &in, std::span<const double> pattern, Polylines &out)
{
    double total = 0;
    for (double length : pattern)
        total += length > 0 ? length : 0;                               // a negative or nan entry adds nothing
    const bool solid = pattern.empty() || !(total >= kMinDashPeriodPx); // nan too
    for (size_t i = 0; i < in.size(); ++i) {
        const auto line = in[i];
        if (line.empty())
            continue;
        if (solid) {
            out.start(line[0]);
            for (size_t j = 1; j < line.size(); ++j)
                out.extend(line[j]);
            continue;
        }
        DashState state{pattern, 0, 0.0};
        state.remaining = state.lengthOf(0);
        dashPolyline(line, state, out);
    }
}

} // namespace overlayd
