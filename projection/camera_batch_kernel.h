// The batch loop over blocks of points, for one lane type: load and transform a block, project it, store it.
//
// Included by camera_batch.cpp (2 lanes) and camera_batch_avx2.cpp (4 lanes) with different OVERLAYD_LANES_NS.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>

#include "camera_batch.h"
#include "point_kernel.h"

namespace overlayd::OVERLAYD_LANES_NS {

// ProjectedPoint is {pixel.x, pixel.y, depth, status + padding}: 32 bytes, status in the low half of the last 8.
static_assert(sizeof(ProjectedPoint) == 4 * sizeof(double) && offsetof(ProjectedPoint, depth) == 16 &&
                  offsetof(ProjectedPoint, status) == 24 && sizeof(PointStatus) == 4,
              "storeRows writes ProjectedPoint as four doubles");
static_assert(std::endian::native == std::endian::little, "storeRows puts the status in the low 4 bytes");

// Stores the lanes of four vectors (pixel x, pixel y, depth, status as integer bits) as whole ProjectedPoints: a
// transpose in registers, then one 32-byte row per point (storing field by field bounced through the stack).
template<class V>
[[gnu::always_inline]] inline void storeRows(V a, V b, V c, V d, ProjectedPoint *out)
{
    if constexpr (kLaneCount<V> == 2) {
        const V rows[4] = {__builtin_shufflevector(a, b, 0, 2), __builtin_shufflevector(c, d, 0, 2),
                           __builtin_shufflevector(a, b, 1, 3), __builtin_shufflevector(c, d, 1, 3)};
        std::memcpy(out, rows, sizeof rows);
    } else if constexpr (kLaneCount<V> == 4) {
        const V t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6), t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);
        const V t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6), t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
        const V rows[4] = {__builtin_shufflevector(t0, t2, 0, 1, 4, 5), __builtin_shufflevector(t1, t3, 0, 1, 4, 5),
                           __builtin_shufflevector(t0, t2, 2, 3, 6, 7), __builtin_shufflevector(t1, t3, 2, 3, 6, 7)};
        std::memcpy(out, rows, sizeof rows);
    } else {
        static_assert(kLaneCount<V> == 8);
        // Pairs (a_i, b_i) and (c_i, d_i) side by side, then two points (64 bytes) per vector.
        const V ab0 = __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11);
        const V ab1 = __builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15);
        const V cd0 = __builtin_shufflevector(c, d, 0, 8, 1, 9, 2, 10, 3, 11);
        const V cd1 = __builtin_shufflevector(c, d, 4, 12, 5, 13, 6, 14, 7, 15);
        const V rows[4] = {__builtin_shufflevector(ab0, cd0, 0, 1, 8, 9, 2, 3, 10, 11),
                           __builtin_shufflevector(ab0, cd0, 4, 5, 12, 13, 6, 7, 14, 15),
                           __builtin_shufflevector(ab1, cd1, 0, 1, 8, 9, 2, 3, 10, 11),
                           __builtin_shufflevector(ab1, cd1, 4, 5, 12, 13, 6, 7, 14, 15)};
        std::memcpy(out, rows, sizeof rows);
    }
}

template<DistortionModel Model, class V>
[[gnu::always_inline]] inline void projectBlock(const PointPath &path, const glm::dmat4 &m, const glm::dvec3 *world,
                                                ProjectedPoint *out)
{
    // Lane by lane: the compiler's inserts measured faster than three loads and shuffles (AVX2: 9 vs 15 ns/point).
    V x, y, z;
    for (int j = 0; j < kLaneCount<V>; ++j) {
        x[j] = world[j].x;
        y[j] = world[j].y;
        z[j] = world[j].z;
    }
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
    const PointPath path = job.path;
    const glm::dmat4 m = job.viewProjection;
    std::size_t i = 0;
    for (; i + N <= job.count; i += N)
        projectBlock<Model, V>(path, m, job.world + i, job.out + i);
    if (i == job.count)
        return;
    // The last few points go through the same block (padded with copies of the last point), so they get the
    // same bits as the others.
    glm::dvec3 world[N];
    ProjectedPoint out[N];
    for (std::size_t j = 0; j < N; ++j)
        world[j] = job.world[std::min(i + j, job.count - 1)];
    projectBlock<Model, V>(path, m, world, out);
    std::copy(out, out + (job.count - i), job.out + i);
}

template<class V>
void projectPointsWith(const BatchJob &job)
{
    switch (job.model) {
    case DistortionModel::None:
        return projectSpan<DistortionModel::None, V>(job);
    case DistortionModel::RadialTangential:
        return projectSpan<DistortionModel::RadialTangential, V>(job);
    case DistortionModel::Rational:
        return projectSpan<DistortionModel::Rational, V>(job);
    case DistortionModel::Fisheye:
        return projectSpan<DistortionModel::Fisheye, V>(job);
    }
}

} // namespace overlayd::OVERLAYD_LANES_NS
