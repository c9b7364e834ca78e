// SPDX-License-Identifier: Apache-2.0
// FrameCoverageSink's pixel steps (frame_coverage_sink.cpp, built with -O3): the premultiplied "over" of
// blend_kernel.cpp with the value and 255 - alpha computed from the opacity on the fly, on one byte, 16 or 8 luma
// lanes and one packed 4:2:2 window, and a short run's opacities loaded straight from its coverage. Header-only so
// that the row paths inline them.
#pragma once

#include <algorithm>
#include <cstdint>

#include "overlay/blend/div255.h"
#include "overlay/blend/sink_lanes.h"

namespace overlayd {

// out = a * value / 255 + in * (255 - a) / 255, each term rounded as the cached path rounds it.
inline uint8_t over(uint8_t in, unsigned a, unsigned value)
{
    return uint8_t(div255(uint16_t(a * value)) + div255(uint16_t(in * (255 - a))));
}

// over() on 16 lanes at once; a lane with opacity 0 comes out exactly as it went in.
inline Bytes16 over16(Bytes16 in, Bytes16 alpha, uint16_t value)
{
    const Words16 a = __builtin_convertvector(alpha, Words16);
    Words16 v = a * value + 128, k = __builtin_convertvector(in, Words16) * (255 - a) + 128;
    v = (v + (v >> 8)) >> 8;
    k = (k + (k >> 8)) >> 8;
    return __builtin_convertvector(v + k, Bytes16);
}

// A thin line's run of up to 16 (step 1) or 8 (step 2, luma in every other byte) pixels as one vector operation:
// the bytes between and after the luma samples see opacity 0 (alpha is staged: zeros follow the run) and are
// written back unchanged.
inline void lumaShort(uint8_t *pixels, unsigned step, unsigned offset, const uint8_t *alpha, unsigned value)
{
    Bytes16 a, in;
    __builtin_memcpy(&a, alpha, 16);
    if (step == 2) {
        const Bytes16 zero{};
        a = offset == 0 ? __builtin_shufflevector(a, zero, 0, 16, 1, 16, 2, 16, 3, 16, 4, 16, 5, 16, 6, 16, 7, 16)
                        : __builtin_shufflevector(a, zero, 16, 0, 16, 1, 16, 2, 16, 3, 16, 4, 16, 5, 16, 6, 16, 7);
    }
    __builtin_memcpy(&in, pixels, 16);
    const Bytes16 out = over16(in, a, uint16_t(value));
    __builtin_memcpy(pixels, &out, 16);
}

// lumaShort for up to 8 one-byte luma samples (planar and semi-planar formats, GREY), opacities in 16-bit lanes.
inline void lumaEight(uint8_t *pixels, Words8 a8, unsigned value)
{
    const Bytes16 in = lowBytes(pixels);
    const Words8 out = div255(Words8(a8 * uint16_t(value))) + div255(Words8(lowWords(in) * (255 - a8)));
    const Bytes8 packed = __builtin_convertvector(out, Bytes8);
    __builtin_memcpy(pixels, &packed, 8);
}

// Eight staged opacities as 16-bit lanes.
inline Words8 eightOpacities(const uint8_t *alpha)
{
    return lowWords(lowBytes(alpha));
}

// A short run's coverage (1..8 bytes) read straight from the producer's row as one word, the bytes past the run
// (there to be read, whatever they hold) cleared: byte k is pixel x0 + k.
inline uint64_t shortCoverage(const uint8_t *coverage, unsigned count)
{
    uint64_t word;
    __builtin_memcpy(&word, coverage, sizeof word);
    return word & (~uint64_t(0) >> (64 - 8 * count));
}

// Coverage bytes (pixel k in byte k) as opacities, scaled by the item's alpha exactly as stage() scales them.
inline uint64_t opacities(uint64_t coverage, unsigned alpha)
{
    if (alpha != 255) {
        const Bytes8 scaled =
            __builtin_convertvector(div255(Words8(lowWords((Bytes16)Longs2{coverage, 0}) * uint16_t(alpha))), Bytes8);
        __builtin_memcpy(&coverage, &scaled, sizeof coverage);
    }
    return coverage;
}

// Adds eight groups' opacity sums from sixteen opacities, a group's two pixels in one 16-bit word (low byte first).
inline void addGroupSums(uint16_t *groups, Words8 pairs)
{
    Words8 sum;
    __builtin_memcpy(&sum, groups, 16);
    sum += (pairs & 0xff) + (pairs >> 8);
    __builtin_memcpy(groups, &sum, 16);
}

// Eight bytes of a word as 16-bit lanes.
inline Words8 wordLanes(uint64_t bytes)
{
    return lowWords((Bytes16)Longs2{bytes, 0});
}

template<unsigned Step>
void lumaLoop(uint8_t *__restrict dst, const uint8_t *__restrict alpha, unsigned count, unsigned value)
{
    for (unsigned i = 0; i < count; ++i)
        dst[i * Step] = over(dst[i * Step], alpha[i], value);
}

template<unsigned Bytes>
void rgbLoop(uint8_t *__restrict dst, const uint8_t *__restrict alpha, unsigned count, const uint8_t *colour,
             const uint8_t *mask)
{
    uint8_t value[Bytes], keep[Bytes];
    std::copy_n(colour, Bytes, value);
    std::copy_n(mask, Bytes, keep);
    for (unsigned i = 0; i < count; ++i) {
        for (unsigned k = 0; k < Bytes; ++k) // an X byte sees opacity 0: it keeps its value
            dst[i * Bytes + k] = over(dst[i * Bytes + k], alpha[i] & keep[k], value[k]);
    }
}

// Each 16-bit word of packed 4:2:2 is one pixel's luma byte and one chroma byte of its macropixel (YUYV: Y0 Cb,
// Y1 Cr, ...), so a window of four macropixels splits into eight luma lanes and eight chroma lanes by shifts. Luma
// takes over()'s rule, chroma chromaLoop's with the macropixel's two opacities summed (shift 1): byte for byte the
// two-pass result. a: the opacities of the window's eight pixels; packedChroma: the chroma lanes' codes at full
// opacity.
[[gnu::always_inline]] inline void blendPackedWindow(uint8_t *bytes, Words8 a, const uint16_t *packedChroma,
                                                     unsigned lumaCode, unsigned lumaOffset)
{
    Words8 chromaCode;
    __builtin_memcpy(&chromaCode, packedChroma, 16);
    const uint16_t luma = uint16_t(lumaCode);
    const unsigned lumaShift = 8 * lumaOffset, chromaShift = 8 - lumaShift;
    // Chroma lanes 2g and 2g + 1 belong to macropixel g: pixels 2g and 2g + 1.
    const Words8 pair = a + __builtin_shufflevector(a, a, 1, 0, 3, 2, 5, 4, 7, 6);
    Words8 words;
    __builtin_memcpy(&words, bytes, 16);
    const Words8 y = (words >> lumaShift) & 0xff, c = (words >> chromaShift) & 0xff;
    const Words8 yOut = div255(Words8(a * luma)) + div255(Words8(y * (255 - a)));
    const Words8 sum4 = pair << 1, cAlpha = meanAlpha8(sum4);
    const Words8 cOut = scaledBySum(sum4, chromaCode, cAlpha) + div255(Words8(c * (255 - cAlpha)));
    const Words8 out = (yOut << lumaShift) | (cOut << chromaShift);
    __builtin_memcpy(bytes, &out, 16);
}

} // namespace overlayd
