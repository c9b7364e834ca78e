// SPDX-License-Identifier: Apache-2.0
// Two blocks of lanes computed side by side: every operation on a LanePair is the same operation on its two halves,
// one after the other, so the instruction stream interleaves two independent blocks of points.
//
// Why: the batch loop's work per block is one long dependency chain (load, transform, a divide, for fisheye a square
// root, an atan with its own divide, the lens polynomial, then the pixel and the store: ~180 cycles on Zen 4), and
// the CPU's out-of-order window holds only a little more than one block of 8-lane instructions (the zmm register
// file: 192 entries for ~140 results per block), so the next block could not start before this one was nearly
// done. Written one block after the other the compiler keeps that order (GCC does not reschedule across the block on
// x86); interleaved, the window holds the early steps of two blocks. A wider generic vector (vector_size(128))
// would say the same thing, but GCC turns its comparisons into scalar code.
//
// The halves see exactly the operations the single block saw, so the bits do not change.
#pragma once

#include "lanes.h"

namespace overlayd::OVERLAYD_LANES_NS {

template<class M>
struct MaskPair {
    M lo, hi;
};

template<class V>
struct LanePair {
    V lo, hi;

    // Reinterpreting casts, as (MaskOf<V>)v and (V)m are for a single vector.
    explicit operator MaskPair<MaskOf<V>>() const { return {(MaskOf<V>)lo, (MaskOf<V>)hi}; }
    LanePair() = default;
    LanePair(V l, V h) : lo(l), hi(h) {}
    explicit LanePair(MaskPair<MaskOf<V>> m) : lo((V)m.lo), hi((V)m.hi) {}
};

template<class V>
inline constexpr bool kIsLanePair = false;
template<class V>
inline constexpr bool kIsLanePair<LanePair<V>> = true;

// Arithmetic: pair with pair, pair with a scalar on either side.
#define OVERLAYD_LANE_PAIR_OPERATOR(op)                                                                                \
    template<class V>                                                                                                  \
    [[gnu::always_inline]] inline LanePair<V> operator op(LanePair<V> a, LanePair<V> b)                                \
    {                                                                                                                  \
        return {a.lo op b.lo, a.hi op b.hi};                                                                           \
    }                                                                                                                  \
    template<class V>                                                                                                  \
    [[gnu::always_inline]] inline LanePair<V> operator op(LanePair<V> a, double b)                                     \
    {                                                                                                                  \
        return {a.lo op b, a.hi op b};                                                                                 \
    }                                                                                                                  \
    template<class V>                                                                                                  \
    [[gnu::always_inline]] inline LanePair<V> operator op(double a, LanePair<V> b)                                     \
    {                                                                                                                  \
        return {a op b.lo, a op b.hi};                                                                                 \
    }
OVERLAYD_LANE_PAIR_OPERATOR(+)
OVERLAYD_LANE_PAIR_OPERATOR(-)
OVERLAYD_LANE_PAIR_OPERATOR(*)
OVERLAYD_LANE_PAIR_OPERATOR(/)
#undef OVERLAYD_LANE_PAIR_OPERATOR

template<class V>
[[gnu::always_inline]] inline LanePair<V> operator-(LanePair<V> a)
{
    return {-a.lo, -a.hi};
}

// Comparisons give a pair of masks.
#define OVERLAYD_LANE_PAIR_COMPARISON(op)                                                                              \
    template<class V>                                                                                                  \
    [[gnu::always_inline]] inline MaskPair<MaskOf<V>> operator op(LanePair<V> a, LanePair<V> b)                        \
    {                                                                                                                  \
        return {a.lo op b.lo, a.hi op b.hi};                                                                           \
    }                                                                                                                  \
    template<class V>                                                                                                  \
    [[gnu::always_inline]] inline MaskPair<MaskOf<V>> operator op(LanePair<V> a, double b)                             \
    {                                                                                                                  \
        return {a.lo op b, a.hi op b};                                                                                 \
    }
OVERLAYD_LANE_PAIR_COMPARISON(<)
OVERLAYD_LANE_PAIR_COMPARISON(<=)
OVERLAYD_LANE_PAIR_COMPARISON(>)
OVERLAYD_LANE_PAIR_COMPARISON(>=)
#undef OVERLAYD_LANE_PAIR_COMPARISON

// Mask logic, and the status arithmetic 1 - mask.
template<class M>
[[gnu::always_inline]] inline MaskPair<M> operator&(MaskPair<M> a, MaskPair<M> b)
{
    return {a.lo & b.lo, a.hi & b.hi};
}
template<class M>
[[gnu::always_inline]] inline MaskPair<M> operator|(MaskPair<M> a, MaskPair<M> b)
{
    return {a.lo | b.lo, a.hi | b.hi};
}
template<class M>
[[gnu::always_inline]] inline MaskPair<M> operator~(MaskPair<M> a)
{
    return {~a.lo, ~a.hi};
}
template<class M>
[[gnu::always_inline]] inline MaskPair<M> operator-(int a, MaskPair<M> b)
{
    return {a - b.lo, a - b.hi};
}

// lanes.h's helpers, half by half.
template<class V>
[[gnu::always_inline]] inline LanePair<V> select(MaskPair<MaskOf<V>> m, LanePair<V> a, LanePair<V> b)
{
    return {select(m.lo, a.lo, b.lo), select(m.hi, a.hi, b.hi)};
}
template<class V>
[[gnu::always_inline]] inline LanePair<V> laneSqrt(LanePair<V> v)
{
    return {laneSqrt(v.lo), laneSqrt(v.hi)};
}
template<class V>
[[gnu::always_inline]] inline LanePair<V> laneAbs(LanePair<V> v)
{
    return {laneAbs(v.lo), laneAbs(v.hi)};
}
template<class V>
[[gnu::always_inline]] inline LanePair<V> laneCopySign(LanePair<V> magnitude, LanePair<V> sign)
{
    return {laneCopySign(magnitude.lo, sign.lo), laneCopySign(magnitude.hi, sign.hi)};
}

} // namespace overlayd::OVERLAYD_LANES_NS
