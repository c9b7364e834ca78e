// SPDX-License-Identifier: Apache-2.0
// Fixed-width double lanes (GCC/Clang vector extensions) and the few helpers the batch kernels need.
//
// Every helper also takes a plain double (one lane, bool masks), so the batch kernels and Camera::project run the
// same template on the same IEEE operations and give the same bits. Helpers live in OVERLAYD_LANES_NS: a
// translation unit compiled for another instruction set (camera_batch_avx2.cpp) defines its own name before
// including, so that the linker never mixes copies compiled for different CPUs.
#pragma once

#include <cmath>
#include <utility>

#ifndef OVERLAYD_LANES_NS
#define OVERLAYD_LANES_NS baseline
#endif

namespace overlayd::OVERLAYD_LANES_NS {

using Lanes2 [[gnu::vector_size(16)]] = double; // SSE2 / NEON register
using Lanes4 [[gnu::vector_size(32)]] = double; // AVX register (only passed by value where AVX is enabled)
using Lanes8 [[gnu::vector_size(64)]] = double; // AVX-512 register (likewise)

// What comparing two V gives: bool for double, a vector of all-ones / all-zeros 64-bit integers for lanes.
template<class V>
using MaskOf = decltype(std::declval<V>() > std::declval<V>());

template<class V>
constexpr int kLaneCount = sizeof(V) / sizeof(double);

[[gnu::always_inline]] inline double select(bool m, double a, double b)
{
    return m ? a : b;
}
template<class V>
[[gnu::always_inline]] inline V select(MaskOf<V> m, V a, V b)
{
    // The vector conditional, not a bitwise blend written out: GCC turned (a & m) | (b & ~m) into two dependent
    // xors per select (b ^ ((a ^ b) & m)), where this is one blend (vblendmpd on a mask register, vblendvpd, bsl).
    return m ? a : b;
}

[[gnu::always_inline]] inline bool maskNot(bool m)
{
    return !m;
}
// bool & bool is an int: still one lane's mask, to be negated logically, not bitwise.
[[gnu::always_inline]] inline bool maskNot(int m)
{
    return m == 0;
}
template<class M>
[[gnu::always_inline]] inline M maskNot(M m)
{
    return ~m;
}

// A mask with every lane set to `value`.
template<class V>
[[gnu::always_inline]] inline MaskOf<V> broadcastMask(bool value)
{
    return V{} + (value ? 1.0 : 0.0) > 0.5;
}

[[gnu::always_inline]] inline double laneSqrt(double v)
{
    return std::sqrt(v);
}
template<class V>
[[gnu::always_inline]] inline V laneSqrt(V v)
{
    // Compiled with -fno-math-errno (camera_batch*.cpp), this loop becomes one sqrtpd.
    V r{};
    for (int i = 0; i < kLaneCount<V>; ++i)
        r[i] = __builtin_sqrt(v[i]);
    return r;
}

[[gnu::always_inline]] inline double laneAbs(double v)
{
    return std::fabs(v);
}
template<class V>
[[gnu::always_inline]] inline V laneAbs(V v)
{
    return (V)((MaskOf<V>)v & ~(MaskOf<V>)(-V{})); // -V{} is -0.0: the sign bit alone
}

[[gnu::always_inline]] inline double laneCopySign(double magnitude, double sign)
{
    return std::copysign(magnitude, sign);
}
template<class V>
[[gnu::always_inline]] inline V laneCopySign(V magnitude, V sign)
{
    const MaskOf<V> signBit = (MaskOf<V>)(-V{});
    return (V)(((MaskOf<V>)magnitude & ~signBit) | ((MaskOf<V>)sign & signBit));
}

} // namespace overlayd::OVERLAYD_LANES_NS
