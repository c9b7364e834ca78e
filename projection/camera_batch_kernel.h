// SPDX-License-Identifier: Apache-2.0
// The batch loop over blocks of points, for one lane type: load and transform a block, project it, store it.
//
// Included by camera_batch.cpp (2-lane registers), camera_batch_avx2.cpp (4) and camera_batch_avx512.cpp (8) with
// different OVERLAYD_LANES_NS. Every loop gives the bits Camera::project gives (batch_projection_test checks it).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>

#include "camera_batch.h"
#include "lane_pair.h"
#include "point_kernel.h"

namespace overlayd::OVERLAYD_LANES_NS {

// ProjectedPoint is {pixel.x, pixel.y, depth, status + padding}: 32 bytes, status in the low half of the last 8.
static_assert(sizeof(ProjectedPoint) == 4 * sizeof(double) && offsetof(ProjectedPoint, depth) == 16 &&
                  offsetof(ProjectedPoint, status) == 24 && sizeof(PointStatus) == 4,
              "storeRows writes ProjectedPoint as four doubles");
static_assert(std::endian::native == std::endian::little, "storeRows puts the status in the low 4 bytes");

// One vector to or from memory that is only 8-byte aligned (a dvec3 or a ProjectedPoint array): one unaligned
// vector load or store. Copying a whole array of vectors with one memcpy instead made GCC stage it on the stack and
// copy it again in pieces of another width (-O2: 16-byte moves; -O3: 8-byte moves through general registers and
// vpinsrq), and a wide load of a value just stored in narrower pieces cannot be forwarded from the store buffer.
template<class V>
[[gnu::always_inline]] inline V loadVector(const double *from)
{
    V v;
    std::memcpy(&v, from, sizeof v);
    return v;
}
template<class V>
[[gnu::always_inline]] inline void storeVector(V v, ProjectedPoint *to, int index)
{
    std::memcpy(reinterpret_cast<char *>(to) + index * sizeof v, &v, sizeof v);
}

// The x, y and z of kLaneCount<V> points (x0 y0 z0 x1 y1 z1 ...) as three vectors: three full-width loads and a
// fixed shuffle per coordinate. Filling the lanes one by one (x[j] = world[j].x) left the choice to GCC's SLP
// vectorizer: at -O2 it found these loads, at -O3 it built each vector from 16-byte loads stored to the stack and
// read back at full width, a store-forwarding stall per vector (the AVX-512 loop at -O3 ran at a third of its speed).
template<class V>
[[gnu::always_inline]] inline void loadPoints(const glm::dvec3 *world, V &x, V &y, V &z)
{
    static_assert(sizeof(glm::dvec3) == 3 * sizeof(double), "dvec3 is three packed doubles");
    const double *p = &world[0].x;
    const V v0 = loadVector<V>(p), v1 = loadVector<V>(p + kLaneCount<V>), v2 = loadVector<V>(p + 2 * kLaneCount<V>);
    if constexpr (kLaneCount<V> == 2) {
        // v0 = x0 y0, v1 = z0 x1, v2 = y1 z1
        x = __builtin_shufflevector(v0, v1, 0, 3);
        y = __builtin_shufflevector(v0, v2, 1, 2);
        z = __builtin_shufflevector(v1, v2, 0, 3);
    } else if constexpr (kLaneCount<V> == 4) {
        // v0 = x0 y0 z0 x1, v1 = y1 z1 x2 y2, v2 = z2 x3 y3 z3: 128-bit halves regrouped, then one in-lane shuffle.
        const V a = __builtin_shufflevector(v0, v1, 0, 1, 6, 7); // x0 y0 x2 y2
        const V b = __builtin_shufflevector(v0, v2, 2, 3, 4, 5); // z0 x1 z2 x3
        const V c = __builtin_shufflevector(v1, v2, 0, 1, 6, 7); // y1 z1 y3 z3
        x = __builtin_shufflevector(a, b, 0, 5, 2, 7);
        y = __builtin_shufflevector(a, c, 1, 4, 3, 6);
        z = __builtin_shufflevector(b, c, 0, 5, 2, 7);
    } else {
        static_assert(kLaneCount<V> == 8);
        // Lanes 0-5 from v0 and v1, lanes 6 and 7 from v2: two two-source permutes (vpermt2pd) per coordinate.
        const V x01 = __builtin_shufflevector(v0, v1, 0, 3, 6, 9, 12, 15, 0, 0);
        const V y01 = __builtin_shufflevector(v0, v1, 1, 4, 7, 10, 13, 0, 0, 0);
        const V z01 = __builtin_shufflevector(v0, v1, 2, 5, 8, 11, 14, 0, 0, 0);
        x = __builtin_shufflevector(x01, v2, 0, 1, 2, 3, 4, 5, 10, 13);
        y = __builtin_shufflevector(y01, v2, 0, 1, 2, 3, 4, 8, 11, 14);
        z = __builtin_shufflevector(z01, v2, 0, 1, 2, 3, 4, 9, 12, 15);
    }
}

// Stores the lanes of four vectors (pixel x, pixel y, depth, status as integer bits) as whole ProjectedPoints: a
// transpose in registers, then one unaligned store per register (storing field by field bounced through the stack).
template<class V>
[[gnu::always_inline]] inline void storeRows(V a, V b, V c, V d, ProjectedPoint *out)
{
    if constexpr (kLaneCount<V> == 2) {
        storeVector(__builtin_shufflevector(a, b, 0, 2), out, 0);
        storeVector(__builtin_shufflevector(c, d, 0, 2), out, 1);
        storeVector(__builtin_shufflevector(a, b, 1, 3), out, 2);
        storeVector(__builtin_shufflevector(c, d, 1, 3), out, 3);
    } else if constexpr (kLaneCount<V> == 4) {
        const V t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6), t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);
        const V t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6), t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
        storeVector(__builtin_shufflevector(t0, t2, 0, 1, 4, 5), out, 0);
        storeVector(__builtin_shufflevector(t1, t3, 0, 1, 4, 5), out, 1);
        storeVector(__builtin_shufflevector(t0, t2, 2, 3, 6, 7), out, 2);
        storeVector(__builtin_shufflevector(t1, t3, 2, 3, 6, 7), out, 3);
    } else {
        static_assert(kLaneCount<V> == 8);
        // Pairs (a_i, b_i) and (c_i, d_i) side by side, then two points (64 bytes) per vector.
        const V ab0 = __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11);
        const V ab1 = __builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15);
        const V cd0 = __builtin_shufflevector(c, d, 0, 8, 1, 9, 2, 10, 3, 11);
        const V cd1 = __builtin_shufflevector(c, d, 4, 12, 5, 13, 6, 14, 7, 15);
        storeVector(__builtin_shufflevector(ab0, cd0, 0, 1, 8, 9, 2, 3, 10, 11), out, 0);
        storeVector(__builtin_shufflevector(ab0, cd0, 4, 5, 12, 13, 6, 7, 14, 15), out, 1);
        storeVector(__builtin_shufflevector(ab1, cd1, 0, 1, 8, 9, 2, 3, 10, 11), out, 2);
        storeVector(__builtin_shufflevector(ab1, cd1, 4, 5, 12, 13, 6, 7, 14, 15), out, 3);
    }
}

// A pair of blocks: the first kLaneCount<V> points, then the next.
template<class V>
[[gnu::always_inline]] inline void loadPoints(const glm::dvec3 *world, LanePair<V> &x, LanePair<V> &y, LanePair<V> &z)
{
    loadPoints(world, x.lo, y.lo, z.lo);
    loadPoints(world + kLaneCount<V>, x.hi, y.hi, z.hi);
}
template<class V>
[[gnu::always_inline]] inline void storeRows(LanePair<V> a, LanePair<V> b, LanePair<V> c, LanePair<V> d,
                                             ProjectedPoint *out)
{
    storeRows(a.lo, b.lo, c.lo, d.lo, out);
    storeRows(a.hi, b.hi, c.hi, d.hi, out + kLaneCount<V>);
}

template<DistortionModel Model, class V>
[[gnu::always_inline]] inline void projectBlock(const PointPath &path, const glm::dmat4 &m, const glm::dvec3 *world,
                                                ProjectedPoint *out)
{
    V x, y, z;
    loadPoints(world, x, y, z);
    // viewProjection * (p, 1) summed in GLM's order ((c0 x + c1 y) + (c2 z + c3)), as Camera::project does.
    const V cx = (m[0][0] * x + m[1][0] * y) + (m[2][0] * z + m[3][0]);
    const V cy = (m[0][1] * x + m[1][1] * y) + (m[2][1] * z + m[3][1]);
    const V cz = (m[0][2] * x + m[1][2] * y) + (m[2][2] * z + m[3][2]);
    const V cw = (m[0][3] * x + m[1][3] * y) + (m[2][3] * z + m[3][3]);
    const ProjectedLanes<V> r = projectClipLanes<Model>(path, cx, cy, cz, cw);
    // A clipped point is ProjectedPoint{}: zeros and PointStatus::Clipped (0); else Outside (1) or Visible (2).
    const MaskOf<V> keep = maskNot(r.clipped);
    const MaskOf<V> status = (1 - r.inScissor) & keep;
    storeRows((V)((MaskOf<V>)r.x & keep), (V)((MaskOf<V>)r.y & keep), (V)((MaskOf<V>)r.depth & keep), (V)status, out);
}

template<DistortionModel Model, class V>
void projectSpan(const BatchJob &job)
{
    constexpr std::size_t N = kLaneCount<V>;
    // Local copies: the stores to out cannot alias them, so they stay in registers across the loop.
    // (The pointers and the count too: read through job, GCC reloaded them after every block's stores.)
    const PointPath path = job.path;
    const glm::dmat4 m = job.viewProjection;
    const glm::dvec3 *const input = job.world;
    ProjectedPoint *const output = job.out;
    const std::size_t count = job.count;
    std::size_t i = 0;
    for (; i + N <= count; i += N)
        projectBlock<Model, V>(path, m, input + i, output + i);
    if (i == count)
        return;
    // The last few points go through the same block (padded with copies of the last point), so they get the
    // same bits as the others.
    glm::dvec3 world[N];
    ProjectedPoint out[N];
    for (std::size_t j = 0; j < N; ++j)
        world[j] = input[std::min(i + j, count - 1)];
    projectBlock<Model, V>(path, m, world, out);
    std::copy(out, out + (count - i), output + i);
}

// V is the CPU's register of lanes. The loops run two blocks of it interleaved (lane_pair.h), fisheye four: its
// chain per block is the longest (a square root and two divides), so it gains from the deeper interleave, where
// the others would only spill more registers.
template<class V>
void projectPointsWith(const BatchJob &job)
{
    using Two = LanePair<V>;
    using Four = LanePair<Two>;
    switch (job.model) {
    case DistortionModel::None:
        return projectSpan<DistortionModel::None, Two>(job);
    case DistortionModel::RadialTangential:
        return projectSpan<DistortionModel::RadialTangential, Two>(job);
    case DistortionModel::Rational:
        return projectSpan<DistortionModel::Rational, Two>(job);
    case DistortionModel::Fisheye:
        return projectSpan<DistortionModel::Fisheye, Four>(job);
    }
}

} // namespace overlayd::OVERLAYD_LANES_NS
