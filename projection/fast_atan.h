// SPDX-License-Identifier: Apache-2.0
// A vectorisable atan for the fisheye model: within 2 ulp of std::atan, no branches, one division.
//
// Reduction to |t| <= tan(pi/8): atan(a) = pi/2 + atan(-1/a) above tan(3 pi/8), pi/4 + atan((a - 1)/(a + 1))
// above tan(pi/8), both written as one division num/den. On the reduced range atan(t) = t + t u P(u), u = t^2,
// where P is a degree-10 Chebyshev fit of (atan(t)/t - 1)/u made in long double (max relative error of the
// whole function 1.2e-16 against atanl; the test fast_atan_test.cpp checks it against std::atan everywhere).
#pragma once

#include "lanes.h"

namespace overlayd::OVERLAYD_LANES_NS {

// pi/2 as a double (its rest is kPiOver2Low below); point_kernel.h's fisheye uses it too.
inline constexpr double kPiOver2 = 1.57079632679489655800;

template<class V>
[[gnu::always_inline]] inline V fastAtan(V x)
{
    static constexpr double kTanPiOver8 = 0.41421356237309504880;
    static constexpr double kTan3PiOver8 = 2.41421356237309504880;
    // pi/2 and pi/4 split into a double and the rest (Cephes' MOREBITS), so the sum keeps the last bit.
    static constexpr double kPiOver2Low = 6.123233995736765886130e-17;
    static constexpr double kPiOver4 = 0.78539816339744827900;
    static constexpr double kPiOver4Low = 3.061616997868382943065e-17;
    static constexpr double kP[] = {
        -0.33333333333333359,  0.20000000000009274,  -0.14285714286408022,  0.11111111116207731,
        -0.090909077923729806, 0.076922446785372869, -0.066652484236908324, 0.058637248389313244,
        -0.05111308797528212,  0.039902708643800196, -0.019923074471281044,
    };
    const V one = V{} + 1.0, zero = V{};
    const V a = laneAbs(x);
    const auto big = a > kTan3PiOver8;
    const auto mid = a > kTanPiOver8;
    const V num = select(big, zero - one, select(mid, a - 1.0, a));
    const V den = select(big, a, select(mid, a + 1.0, one));
    const V t = num / den;
    const V base = select(big, zero + kPiOver2, select(mid, zero + kPiOver4, zero));
    const V baseLow = select(big, zero + kPiOver2Low, select(mid, zero + kPiOver4Low, zero));
    // Estrin's scheme: the same terms as Horner's, but a chain of 4 multiply-adds instead of 10, so that the
    // batch loop is not held up by the latency of one long chain.
    const V u = t * t, u2 = u * u, u4 = u2 * u2, u8 = u4 * u4;
    const V q0 = kP[0] + kP[1] * u, q1 = kP[2] + kP[3] * u, q2 = kP[4] + kP[5] * u;
    const V q3 = kP[6] + kP[7] * u, q4 = kP[8] + kP[9] * u;
    const V p = ((q0 + q1 * u2) + (q2 + q3 * u2) * u4) + (q4 + kP[10] * u2) * u8;
    const V reduced = t + t * (u * p);
    return laneCopySign(base + (reduced + baseLow), x);
}

} // namespace overlayd::OVERLAYD_LANES_NS
