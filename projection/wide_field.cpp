// SPDX-License-Identifier: Apache-2.0
// WideField: a segment is cut where it crosses the near sphere, the far plane or the back cone; the pieces
// between those crossings are each wholly in or out of the field, so testing their midpoints sorts them.
#include "wide_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace overlayd {

namespace {

// Up to ten parameters where the segment crosses a boundary, with 0 and 1.
struct Breaks {
    std::array<double, 10> t{};
    int count = 0;
    void add(double value)
    {
        if (value > 0.0 && value < 1.0 && count < static_cast<int>(t.size()))
            t[count++] = value;
    }
    // Real roots of a t^2 + b t + c, in the numerically stable form.
    void addRoots(double a, double b, double c)
    {
        if (std::abs(a) < 1e-300) {
            if (std::abs(b) >= 1e-300)
                add(-c / b);
            return;
        }
        const double disc = b * b - 4.0 * a * c;
        if (disc < 0.0)
            return;
        const double k = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        add(k / a);
        if (k != 0.0)
            add(c / k);
    }
};

} // namespace

glm::dvec3 WideField::optical(const glm::dvec4 &clip) const
{
    return {toNormalized * glm::dvec2(clip) + toNormalizedW * clip.w, clip.w};
}

bool WideField::inside(const glm::dvec4 &clip) const
{
    const glm::dvec3 o = optical(clip);
    const double rw2 = o.x * o.x + o.y * o.y;
    const bool finite = std::abs(clip.w) <= std::numeric_limits<double>::max();
    const bool inField = clip.w >= 0.0 || rw2 >= backSlope2 * (clip.w * clip.w);
    return finite && rw2 + clip.w * clip.w >= near2 && inField && !(hasFar && clip.w - clip.z < 0.0);
}

SegmentPieces WideField::pieces(const glm::dvec4 &a, const glm::dvec4 &b) const
{
    const glm::dvec4 d = b - a;
    const glm::dvec3 o0 = optical(a), o1 = optical(b) - o0;
    Breaks breaks;
    if (hasFar && std::abs(d.w - d.z) >= 1e-300)
        breaks.add(-(a.w - a.z) / (d.w - d.z));
    // |o(t)|^2 = near^2, and |xy(t)|^2 = backSlope2 z(t)^2 (both nappes; the midpoint test keeps the right one).
    breaks.addRoots(glm::dot(o1, o1), 2.0 * glm::dot(o0, o1), glm::dot(o0, o0) - near2);
    const glm::dvec2 p0(o0), p1(o1);
    breaks.addRoots(glm::dot(p1, p1) - backSlope2 * o1.z * o1.z, 2.0 * (glm::dot(p0, p1) - backSlope2 * o0.z * o1.z),
                    glm::dot(p0, p0) - backSlope2 * o0.z * o0.z);
    std::array<double, 12> t{};
    t[0] = 0.0;
    std::copy(breaks.t.begin(), breaks.t.begin() + breaks.count, t.begin() + 1);
    const int n = breaks.count + 2;
    t[n - 1] = 1.0;
    std::sort(t.begin(), t.begin() + n);
    SegmentPieces out;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(t[i + 1] > t[i]) || !inside(a + 0.5 * (t[i] + t[i + 1]) * d))
            continue;
        if (out.count > 0 && out.ranges[out.count - 1][1] == t[i])
            out.ranges[out.count - 1][1] = t[i + 1];
        else if (out.count < static_cast<int>(out.ranges.size()))
            out.ranges[out.count++] = {t[i], t[i + 1]};
    }
    return out;
}

} // namespace overlayd
