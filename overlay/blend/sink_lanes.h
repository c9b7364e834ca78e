// SPDX-License-Identifier: Apache-2.0
// The 16-bit lane arithmetic the overlay's blend kernels share (FrameCoverageSink's, and blend_kernel.cpp's short
// runs): vector types, loads, and the chroma rule on scalars and on eight lanes.
#pragma once

#include <algorithm>
#include <cstdint>

namespace overlayd {

using Bytes16 = uint8_t __attribute__((vector_size(16)));
using Bytes8 = uint8_t __attribute__((vector_size(8)));
using Words16 = uint16_t __attribute__((vector_size(32)));
using Words8 = uint16_t __attribute__((vector_size(16)));
using Shorts8 = int16_t __attribute__((vector_size(16)));
using Longs2 = uint64_t __attribute__((vector_size(16)));

// Opacity scaled to a four-pixel sum, rounded half to even as the cached path's lrintf rounds the mean.
inline unsigned meanAlpha(unsigned sum4)
{
    return (sum4 + 1 + ((sum4 >> 2) & 1)) >> 2;
}

// A code at full opacity scaled to the mean opacity sum4 / 4; never above alpha, so the blend cannot overflow.
inline unsigned scaled(unsigned sum4, unsigned code, unsigned alpha)
{
    return std::min((sum4 * code + 510) / 1020, alpha);
}

// scaled() on 8 lanes of four-pixel sums (s <= 1020), in 16-bit lanes: with s = 4q + r, floor((s * code + 510) / 4)
// = q * code + floor((r * code + 510) / 4) <= 65152, and floor(y / 255) == (y + 1 + (y >> 8)) >> 8 for y < 65535
// (checked for every sum and code). Value and cap are at most 1020: a signed minimum (one SSE2 instruction) does.
inline Words8 scaledBySum(Words8 s, Words8 code, Words8 alpha)
{
    const Words8 y = (s >> 2) * code + (((s & 3) * code + 510) >> 2);
    const Shorts8 value = (Shorts8)((y + 1 + (y >> 8)) >> 8), cap = (Shorts8)alpha;
    return (Words8)(value < cap ? value : cap);
}

// meanAlpha() on 8 lanes.
inline Words8 meanAlpha8(Words8 sum4)
{
    return (sum4 + 1 + ((sum4 >> 2) & 1)) >> 2;
}

// Eight bytes from p in the low half of a vector, the high half 0 (one 64-bit load).
inline Bytes16 lowBytes(const uint8_t *p)
{
    uint64_t word;
    __builtin_memcpy(&word, p, sizeof word);
    return (Bytes16)Longs2{word, 0};
}

// Bytes 0-7 of v as 16-bit lanes.
inline Words8 lowWords(Bytes16 v)
{
    return (Words8)__builtin_shufflevector(v, Bytes16{}, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
}

} // namespace overlayd
