// SPDX-License-Identifier: Apache-2.0
// Polygon spans: a scanline fill at pixel centres with the nonzero winding rule.
#include "overlay/raster/polygon_spans.h"

#include <algorithm>
#include <cmath>

namespace overlayd {

namespace {

// Far enough outside any frame to change nothing, near enough that every product below stays exact in a double.
constexpr double kFar = 1e7;

struct Crossing {
    double x;
    int winding;
};

glm::dvec2 clamped(const glm::dvec2 &p)
{
    return {std::clamp(p.x, -kFar, kFar), std::clamp(p.y, -kFar, kFar)};
}

// The first pixel whose centre is at or right of x.
int firstCentreAtOrAfter(double x)
{
    return int(std::ceil(x - 0.5));
}

} // namespace

void polygonSpans(std::span<const glm::dvec2> polygon, int width, int height, std::vector<RowSpan> &out)
{
    if (polygon.size() < 3 || width <= 0 || height <= 0)
        return;
    double low = kFar, high = -kFar;
    for (const glm::dvec2 &p : polygon)
        low = std::min(low, clamped(p).y), high = std::max(high, clamped(p).y);
    const int y0 = std::max(0, firstCentreAtOrAfter(low)), y1 = std::min(height, firstCentreAtOrAfter(high));
    std::vector<Crossing> crossings;
    for (int y = y0; y < y1; ++y) {
        const double centre = y + 0.5;
        crossings.clear();
        for (size_t i = 0; i < polygon.size(); ++i) {
            const glm::dvec2 a = clamped(polygon[i]), b = clamped(polygon[(i + 1) % polygon.size()]);
            // Half-open in y, so a vertex on the scanline counts once and a horizontal edge never.
            const bool down = a.y <= centre && centre < b.y, up = b.y <= centre && centre < a.y;
            if (down || up)
                crossings.push_back({a.x + (centre - a.y) * (b.x - a.x) / (b.y - a.y), down ? 1 : -1});
        }
        std::sort(crossings.begin(), crossings.end(), [](const Crossing &l, const Crossing &r) { return l.x < r.x; });
        int winding = 0;
        for (size_t i = 0; i + 1 < crossings.size(); ++i) {
            winding += crossings[i].winding;
            if (winding == 0)
                continue;
            const int x0 = std::max(0, firstCentreAtOrAfter(crossings[i].x));
            const int x1 = std::min(width, firstCentreAtOrAfter(crossings[i + 1].x));
            if (x0 < x1)
                out.push_back({y, x0, x1});
        }
    }
}

SpanRows::SpanRows(std::vector<RowSpan> spans, unsigned width, unsigned height, unsigned hSub, unsigned vSub)
{
    std::vector<RowSpan> grown;
    for (RowSpan s : spans) {
        s.x0 = std::max(0, s.x0) / int(hSub) * int(hSub);
        s.x1 = std::min(int(width), (std::min(int(width), s.x1) + int(hSub) - 1) / int(hSub) * int(hSub));
        if (s.y < 0 || s.y >= int(height) || s.x0 >= s.x1)
            continue;
        // Every row of the span's group of vSub rows (a 4:2:0 chroma row serves two luma rows).
        for (int y = s.y / int(vSub) * int(vSub); y < std::min(int(height), (s.y / int(vSub) + 1) * int(vSub)); ++y)
            grown.push_back({y, s.x0, std::min(s.x1, int(width))});
    }
    std::sort(grown.begin(), grown.end(),
              [](const RowSpan &a, const RowSpan &b) { return a.y != b.y ? a.y < b.y : a.x0 < b.x0; });
    for (const RowSpan &s : grown) {
        if (!spans_.empty() && spans_.back().y == s.y && s.x0 <= spans_.back().x1)
            spans_.back().x1 = std::max(spans_.back().x1, s.x1);
        else
            spans_.push_back(s);
    }
    rowStart_.assign(size_t(height) + 1, 0);
    size_t next = 0;
    for (unsigned y = 0; y <= height; ++y) {
        while (next < spans_.size() && spans_[next].y < int(y))
            ++next;
        rowStart_[y] = uint32_t(next);
    }
}

uint64_t SpanRows::area() const
{
    uint64_t total = 0;
    for (const RowSpan &s : spans_)
        total += uint64_t(s.x1 - s.x0);
    return total;
}

} // namespace overlayd
