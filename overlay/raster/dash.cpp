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
        remaining = pattern[index];
    }
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
        total += length > 0 ? length : 0;
    const bool solid = pattern.empty() || total <= 0;
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
        dashPolyline(line, DashState{pattern, 0, pattern[0]}, out);
    }
}

} // namespace overlayd
