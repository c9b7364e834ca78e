// SPDX-License-Identifier: Apache-2.0
// The per-point projection from clip space to a pixel and a status, written once for any lane type.
//
// Camera::project runs it on one double, the batch loops (camera_batch*.cpp) on 2 or 4 lanes. Same operations in
// the same order, no fused multiply-add (the files are built with -ffp-contract=off): the same bits either way.
#pragma once

#include <array>
#include <limits>

#include "distortion.h"
#include "fast_atan.h"
#include "lanes.h"
#include "point_path.h"

namespace overlayd::OVERLAYD_LANES_NS {

template<class V>
struct ProjectedLanes {
    V x, y, depth; // meaningful where not clipped
    MaskOf<V> clipped, inScissor;
};

// The distorted normalized point (dx, dy) of the normalized point (sx, sy) / w, given inverseW = 1 / w.
template<DistortionModel Model, class V>
[[gnu::always_inline]] inline void distortLanes(const std::array<double, 8> &c, V sx, V sy, V inverseW, V &dx, V &dy)
{
    if constexpr (Model == DistortionModel::Fisheye) {
        // OpenCV's fisheye: theta = atan(r), theta_d = theta (1 + k1 theta^2 + ... + k4 theta^8), scale theta_d/r.
        // r is taken from w r = |(sx, sy)| so that the square root and 1 / (w r) run beside the 1 / w divide
        // rather than after it; the polynomial is evaluated in Estrin's form for the same reason.
        const V rw = laneSqrt(sx * sx + sy * sy);
        const V inverseRw = 1.0 / rw;
        const V r = rw * inverseW;
        const V theta = fastAtan(r);
        const V t2 = theta * theta, t4 = t2 * t2;
        const V thetaD = theta * (1.0 + t2 * ((c[0] + c[1] * t2) + (c[2] + c[3] * t2) * t4));
        // OpenCV's guard: below r = 1e-8 the ratio theta_d / r tends to 1.
        const V scale = select(r > 1e-8, thetaD * inverseRw, inverseW);
        dx = sx * scale;
        dy = sy * scale;
    } else {
        // OpenCV's 5- and 8-coefficient models; the 5-coefficient one has no denominator.
        const V x = sx * inverseW, y = sy * inverseW;
        const V r2 = x * x + y * y;
        const V r4 = r2 * r2, r6 = r4 * r2;
        V radial = 1.0 + c[0] * r2 + c[1] * r4 + c[4] * r6;
        if constexpr (Model == DistortionModel::Rational)
            radial = radial / (1.0 + c[5] * r2 + c[6] * r4 + c[7] * r6);
        const V a1 = 2.0 * x * y;
        dx = x * radial + c[2] * a1 + c[3] * (r2 + 2.0 * x * x);
        dy = y * radial + c[2] * (r2 + 2.0 * y * y) + c[3] * a1;
    }
}

template<class V>
[[gnu::always_inline]] inline MaskOf<V> inScissor(const PointPath &p, V x, V y)
{
    return (x >= p.scissorMin.x) & (x <= p.scissorMax.x) & (y >= p.scissorMin.y) & (y <= p.scissorMax.y);
}

// A fisheye of more than 180 degrees: theta = atan2(|(X, Y)|, Z) rather than atan(|(X, Y)| / Z), which ends at
// the camera plane. In front of it (w > 0) the operations are those of distortLanes, so the pixels agree with a
// narrower lens's; the near plane becomes the near sphere (a plane would cut off the field behind the camera).
template<class V>
[[gnu::always_inline]] inline ProjectedLanes<V> projectWideFisheye(const PointPath &p, V cx, V cy, V cz, V cw)
{
    ProjectedLanes<V> out;
    const V sx = p.toNormalized[0][0] * cx + p.toNormalized[1][0] * cy + p.toNormalizedW.x * cw;
    const V sy = p.toNormalized[0][1] * cx + p.toNormalized[1][1] * cy + p.toNormalizedW.y * cw;
    const V rw2 = sx * sx + sy * sy;
    const MaskOf<V> finite = laneAbs(cw) <= std::numeric_limits<double>::max();
    const MaskOf<V> pastNear = rw2 + cw * cw >= p.near2;
    const MaskOf<V> inField = (cw >= 0.0) | (rw2 >= p.backSlope2 * (cw * cw));
    const MaskOf<V> hasFar = broadcastMask<V>(p.hasFar);
    out.clipped = maskNot(finite & pastNear & inField) | (hasFar & (cw - cz < 0.0));
    const V inverseW = 1.0 / cw;
    out.depth = cz * inverseW;
    const V rw = laneSqrt(rw2);
    const V inverseRw = 1.0 / rw;
    const V r = rw * inverseW;
    const MaskOf<V> front = cw > 0.0;
    // Behind the plane atan2(rw, w) = pi/2 - atan(w / rw): one atan either way.
    const V zero = V{};
    const V angle = fastAtan(select(front, r, cw * inverseRw));
    const V theta = select(front, angle, (zero + kPiOver2) - angle);
    const std::array<double, 8> &c = p.coeffs;
    const V t2 = theta * theta, t4 = t2 * t2;
    const V thetaD = theta * (1.0 + t2 * ((c[0] + c[1] * t2) + (c[2] + c[3] * t2) * t4));
    const V scale = select(front & maskNot(r > 1e-8), inverseW, thetaD * inverseRw);
    const V dx = sx * scale, dy = sy * scale;
    out.x = p.toPixel[0][0] * dx + p.toPixel[1][0] * dy + p.toPixelOffset.x;
    out.y = p.toPixel[0][1] * dx + p.toPixel[1][1] * dy + p.toPixelOffset.y;
    out.inScissor = inScissor(p, out.x, out.y);
    return out;
}

template<DistortionModel Model, class V>
[[gnu::always_inline]] inline ProjectedLanes<V> projectClipLanes(const PointPath &p, V cx, V cy, V cz, V cw)
{
    ProjectedLanes<V> out;
    // In front (w > 0, which also refuses NaN), not nearer than near, not beyond far: tested before any divide.
    // w must also be finite: a non-finite or overflowing input point would otherwise get a NaN pixel.
    // (Named masks, not calls inside | and &: clang warns about bitwise operators on bools next to calls.)
    const MaskOf<V> notInFront = maskNot((cw > 0.0) & (cw <= std::numeric_limits<double>::max()));
    const MaskOf<V> hasFar = broadcastMask<V>(p.hasFar);
    if constexpr (Model == DistortionModel::Fisheye) {
        if (p.wide)
            return projectWideFisheye(p, cx, cy, cz, cw);
    }
    out.clipped = notInFront | (cz + p.nearW * cw < 0.0) | (hasFar & (cw - cz < 0.0));
    // One division per point; clipped lanes go through the maths too (nothing traps) and are discarded.
    const V inverseW = 1.0 / cw;
    out.depth = cz * inverseW;
    if constexpr (Model == DistortionModel::None) {
        out.x = cx * inverseW * p.toPixel[0][0] + p.toPixelOffset.x;
        out.y = cy * inverseW * p.toPixel[1][1] + p.toPixelOffset.y;
    } else {
        // w * normalized coordinates is linear in the clip point: the lens cone test needs no divide.
        const V sx = p.toNormalized[0][0] * cx + p.toNormalized[1][0] * cy + p.toNormalizedW.x * cw;
        const V sy = p.toNormalized[0][1] * cx + p.toNormalized[1][1] * cy + p.toNormalizedW.y * cw;
        const MaskOf<V> outsideCone = maskNot(sx * sx + sy * sy <= p.validRadius2 * cw * cw);
        out.clipped = out.clipped | outsideCone;
        V dx, dy;
        distortLanes<Model>(p.coeffs, sx, sy, inverseW, dx, dy);
        out.x = p.toPixel[0][0] * dx + p.toPixel[1][0] * dy + p.toPixelOffset.x;
        out.y = p.toPixel[0][1] * dx + p.toPixel[1][1] * dy + p.toPixelOffset.y;
    }
    out.inScissor = inScissor(p, out.x, out.y);
    return out;
}

} // namespace overlayd::OVERLAYD_LANES_NS
