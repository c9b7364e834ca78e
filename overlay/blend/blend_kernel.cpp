// SPDX-License-Identifier: Apache-2.0
// The blend loops: short runs (the common case: a few pixels of a thin line) as one 16-byte vector operation with
// a lane mask, long runs as plain loops the compiler vectorizes (16-bit lanes); built with -O3 for that reason.
#include "overlay/blend/blend_kernel.h"

#include "overlay/blend/div255.h"
#include "overlay/blend/sink_lanes.h"

namespace overlayd {

namespace {

inline void blendInline(uint8_t *__restrict dst, const uint8_t *__restrict values,
                        const uint8_t *__restrict inverseAlpha, size_t count)
{
    for (size_t i = 0; i < count; ++i) {
        dst[i] = uint8_t(values[i] + div255(uint16_t(dst[i] * inverseAlpha[i])));
    }
}

using Bytes16 = uint8_t __attribute__((vector_size(16)));
using Words16 = uint16_t __attribute__((vector_size(32)));

Bytes16 load16(const uint8_t *p)
{
    Bytes16 v;
    __builtin_memcpy(&v, p, 16);
    return v;
}

// The first `count` (< 16) bytes of dst blended, the other 16 - count lanes written back as they were. Reads 16
// bytes at each pointer: the caller guarantees they exist (the layer pads its arrays, the frame check is per run).
inline void blendMasked16(uint8_t *dst, const uint8_t *values, const uint8_t *inverseAlpha, unsigned count)
{
    static constexpr Bytes16 kLane = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    const Bytes16 in = load16(dst);
    const Words16 x =
        __builtin_convertvector(in, Words16) * __builtin_convertvector(load16(inverseAlpha), Words16) + 128;
    const Bytes16 out = load16(values) + __builtin_convertvector((x + (x >> 8)) >> 8, Bytes16);
    const Bytes16 result = kLane < uint8_t(count) ? out : in;
    __builtin_memcpy(dst, &result, 16);
}

// blendMasked16 for count <= 8 bytes (a thin line's run in a one-byte-per-sample plane): half the lanes, 16-bit
// lanes in one register. Reads 8 bytes at each pointer.
inline void blendMasked8(uint8_t *dst, const uint8_t *values, const uint8_t *inverseAlpha, unsigned count)
{
    static constexpr Words8 kLane = {0, 1, 2, 3, 4, 5, 6, 7};
    const Words8 in = lowWords(lowBytes(dst)), x = in * lowWords(lowBytes(inverseAlpha)) + 128;
    const Words8 out = lowWords(lowBytes(values)) + ((x + (x >> 8)) >> 8);
    const Bytes8 result = __builtin_convertvector(kLane < uint16_t(count) ? out : in, Bytes8);
    __builtin_memcpy(dst, &result, 8);
}

uint8_t *address(const FrameView &frame, const NativeRun &run)
{
    const PlaneView &plane = frame.planes[run.plane];
    return plane.data + size_t(run.row) * plane.stride + run.byteOffset;
}

} // namespace

void blendBytes(uint8_t *__restrict dst, const uint8_t *__restrict values, const uint8_t *__restrict inverseAlpha,
                size_t count)
{
    blendInline(dst, values, inverseAlpha, count);
}

void blendRuns(const FrameView &frame, std::span<const NativeRun> runs, const uint8_t *values,
               const uint8_t *inverseAlpha)
{
    // Runs are scattered over rows, so a cold frame costs a memory latency per run unless the misses overlap:
    // prefetching some runs ahead lets them (it halved the cold 1080p blend in tests/bench_overlay).
    constexpr size_t kPrefetchAhead = 16;
    for (size_t i = 0; i < runs.size(); ++i) {
        if (i + kPrefetchAhead < runs.size())
            __builtin_prefetch(address(frame, runs[i + kPrefetchAhead]), 1);
        const NativeRun &run = runs[i];
        uint8_t *dst = address(frame, run);
        const PlaneView &plane = frame.planes[run.plane];
        if (run.length <= 8 && dst + 16 <= plane.data + plane.size)
            blendMasked8(dst, values + run.dataOffset, inverseAlpha + run.dataOffset, run.length);
        else if (run.length < 16 && dst + 16 <= plane.data + plane.size)
            blendMasked16(dst, values + run.dataOffset, inverseAlpha + run.dataOffset, run.length);
        else
            blendInline(dst, values + run.dataOffset, inverseAlpha + run.dataOffset, run.length);
    }
}

} // namespace overlayd
