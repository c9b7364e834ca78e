// FrameCoverageSink's pixel loops: the premultiplied "over" of blend_kernel.cpp with the value and 255 - alpha
// computed from the opacity on the fly, in 16-bit lanes the compiler vectorizes (built with -O3).
#include "overlay/frame_coverage_sink.h"

#include "overlay/div255.h"

#include <algorithm>
#include <cassert>

namespace overlayd {

namespace {

// out = a * value / 255 + in * (255 - a) / 255, each term rounded as the cached path rounds it.
inline uint8_t over(uint8_t in, unsigned a, unsigned value)
{
    return uint8_t(div255(uint16_t(a * value)) + div255(uint16_t(in * (255 - a))));
}

using Bytes16 = uint8_t __attribute__((vector_size(16)));
using Words16 = uint16_t __attribute__((vector_size(32)));

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
// the bytes between and after the luma samples see opacity 0 and are written back unchanged.
inline void lumaShort(uint8_t *pixels, unsigned step, unsigned offset, const uint8_t *alpha, unsigned count,
                      unsigned value)
{
    Bytes16 a{}, in;
    __builtin_memcpy(&a, alpha, count);
    if (step == 2) {
        const Bytes16 zero{};
        a = offset == 0 ? __builtin_shufflevector(a, zero, 0, 16, 1, 16, 2, 16, 3, 16, 4, 16, 5, 16, 6, 16, 7, 16)
                        : __builtin_shufflevector(a, zero, 16, 0, 16, 1, 16, 2, 16, 3, 16, 4, 16, 5, 16, 6, 16, 7);
    }
    __builtin_memcpy(&in, pixels, 16);
    const Bytes16 out = over16(in, a, uint16_t(value));
    __builtin_memcpy(pixels, &out, 16);
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

template<unsigned Step>
void chromaLoop(uint8_t *__restrict cb, uint8_t *__restrict cr, uint16_t *__restrict sums, unsigned count,
                unsigned shift, unsigned cbCode, unsigned crCode)
{
    for (unsigned g = 0; g < count; ++g) {
        const unsigned sum4 = unsigned(sums[g]) << shift, alpha = meanAlpha(sum4);
        sums[g] = 0; // ready for the next chroma row
        const uint16_t keep = uint16_t(255 - alpha);
        cb[g * Step] = uint8_t(scaled(sum4, cbCode, alpha) + div255(uint16_t(cb[g * Step] * keep)));
        cr[g * Step] = uint8_t(scaled(sum4, crCode, alpha) + div255(uint16_t(cr[g * Step] * keep)));
    }
}

using Words8 = uint16_t __attribute__((vector_size(16)));
using Longs8 = uint32_t __attribute__((vector_size(32)));
using Bytes8 = uint8_t __attribute__((vector_size(8)));

// scaled() on 8 lanes without a division: floor(n / 1020) == floor(floor(n / 4) / 255), and floor(y / 255) ==
// (y + 1 + (y >> 8)) >> 8 for y < 65535 (checked for every sum and code).
inline Words8 scaled8(Words8 sum4, unsigned code, Words8 alpha)
{
    const Longs8 y = (__builtin_convertvector(sum4, Longs8) * code + 510) >> 2;
    const Words8 value = __builtin_convertvector((y + 1 + (y >> 8)) >> 8, Words8);
    return value < alpha ? value : alpha;
}

// Eight groups' opacity sums taken (and zeroed, ready for the next chroma row) and their two chroma samples, given
// and returned as 16-bit lanes, blended by chromaLoop's rule.
inline void blendEightGroups(uint16_t *sums, unsigned shift, unsigned firstCode, unsigned secondCode, Words8 &first,
                             Words8 &second)
{
    Words8 sum;
    __builtin_memcpy(&sum, sums, 16);
    __builtin_memset(sums, 0, 16);
    sum = sum << shift;
    const Words8 alpha = (sum + 1 + ((sum >> 2) & 1)) >> 2, keep = 255 - alpha;
    first = scaled8(sum, firstCode, alpha) + div255(Words8(first * keep));
    second = scaled8(sum, secondCode, alpha) + div255(Words8(second * keep));
}

// NV12/NV21: Cb and Cr interleaved in one plane, eight groups (16 bytes) per step, then chromaLoop's scalar rule.
void chromaInterleaved(uint8_t *pairs, uint16_t *sums, unsigned count, unsigned shift, unsigned firstCode,
                       unsigned secondCode)
{
    unsigned g = 0;
    for (; g + 8 <= count; g += 8) {
        Bytes16 bytes;
        __builtin_memcpy(&bytes, pairs + 2 * g, 16);
        Words8 first =
            __builtin_convertvector(__builtin_shufflevector(bytes, bytes, 0, 2, 4, 6, 8, 10, 12, 14), Words8);
        Words8 second =
            __builtin_convertvector(__builtin_shufflevector(bytes, bytes, 1, 3, 5, 7, 9, 11, 13, 15), Words8);
        blendEightGroups(sums + g, shift, firstCode, secondCode, first, second);
        const Bytes8 a = __builtin_convertvector(first, Bytes8), b = __builtin_convertvector(second, Bytes8);
        bytes = __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11, 4, 12, 5, 13, 6, 14, 7, 15);
        __builtin_memcpy(pairs + 2 * g, &bytes, 16);
    }
    chromaLoop<2>(pairs + 2 * g, pairs + 2 * g + 1, sums + g, count - g, shift, firstCode, secondCode);
}

using Bytes32 = uint8_t __attribute__((vector_size(32)));

// Packed 4:2:2 (YUYV, UYVY, YVYU): the two chroma bytes of a group are 2 apart, groups 4 apart; eight groups (32
// bytes) per step, the luma bytes between written back as read. The 32nd byte belongs to the group after the eight,
// so a step needs one more group in the interval.
void chromaPacked(uint8_t *pairs, uint16_t *sums, unsigned count, unsigned shift, unsigned firstCode,
                  unsigned secondCode)
{
    unsigned g = 0;
    for (; g + 8 < count; g += 8) {
        Bytes32 bytes;
        __builtin_memcpy(&bytes, pairs + 4 * g, 32);
        Words8 first =
            __builtin_convertvector(__builtin_shufflevector(bytes, bytes, 0, 4, 8, 12, 16, 20, 24, 28), Words8);
        Words8 second =
            __builtin_convertvector(__builtin_shufflevector(bytes, bytes, 2, 6, 10, 14, 18, 22, 26, 30), Words8);
        blendEightGroups(sums + g, shift, firstCode, secondCode, first, second);
        const Bytes8 a = __builtin_convertvector(first, Bytes8), b = __builtin_convertvector(second, Bytes8);
        const Bytes16 ab = __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        const Bytes32 blended = __builtin_shufflevector(ab, ab, 0, 0, 8, 0, 1, 0, 9, 0, 2, 0, 10, 0, 3, 0, 11, 0, 4, 0,
                                                        12, 0, 5, 0, 13, 0, 6, 0, 14, 0, 7, 0, 15, 0);
        static constexpr Bytes32 kChroma = {0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0,
                                            0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0, 0xff, 0};
        bytes = (blended & kChroma) | (bytes & ~kChroma);
        __builtin_memcpy(pairs + 4 * g, &bytes, 32);
    }
    chromaLoop<4>(pairs + 4 * g, pairs + 4 * g + 2, sums + g, count - g, shift, firstCode, secondCode);
}

} // namespace

void FrameCoverageSink::blendLuma(uint8_t *pixels, const Layout &layout, const uint8_t *alpha, unsigned count,
                                  unsigned value, size_t room)
{
    const unsigned step = layout.lumaStep;
    assert(step == 1 || step == 2);
    // A long run (a flat line near the camera) as whole 16-byte vectors too, then its remainder.
    const unsigned perVector = 16 / step;
    while (count > perVector && room >= 32) {
        lumaShort(pixels, step, layout.lumaOffset, alpha, perVector, value);
        pixels += 16, room -= 16, alpha += perVector, count -= perVector;
    }
    if (count * step <= 16 && room >= 16)
        return lumaShort(pixels, step, layout.lumaOffset, alpha, count, value);
    uint8_t *dst = pixels + layout.lumaOffset;
    if (step == 1)
        lumaLoop<1>(dst, alpha, count, value);
    else
        lumaLoop<2>(dst, alpha, count, value);
}

void FrameCoverageSink::blendRgb(uint8_t *dst, unsigned pixelBytes, const uint8_t *alpha, unsigned count,
                                 const ItemColour &colour)
{
    assert(pixelBytes == 3 || pixelBytes == 4);
    if (pixelBytes == 3)
        rgbLoop<3>(dst, alpha, count, colour.rgb, colour.rgbMask);
    else
        rgbLoop<4>(dst, alpha, count, colour.rgb, colour.rgbMask);
}

void FrameCoverageSink::accumulateAlpha(uint16_t *sums, unsigned x0, const uint8_t *alpha, unsigned count)
{
    unsigned i = 0;
    if (x0 % 2 == 1) // the first pixel is the second of its group
        sums[x0 / 2] = uint16_t(sums[x0 / 2] + alpha[i++]);
    uint16_t *__restrict group = sums + (x0 + i) / 2;
    const unsigned pairs = (count - i) / 2;
    for (unsigned p = 0; p < pairs; ++p)
        group[p] = uint16_t(group[p] + alpha[i + 2 * p] + alpha[i + 2 * p + 1]);
    if ((count - i) % 2 == 1)
        group[pairs] = uint16_t(group[pairs] + alpha[count - 1]);
}

void FrameCoverageSink::blendChroma(uint8_t *cb, uint8_t *cr, unsigned step, uint16_t *sums, unsigned count,
                                    unsigned shift, const ItemColour &colour)
{
    // Packed 4:2:2 keeps Cb and Cr in one plane, 2 bytes apart: the loops never write the same byte through both.
    if (step == 1)
        chromaLoop<1>(cb, cr, sums, count, shift, colour.cb, colour.cr);
    else if (step == 2 && cr == cb + 1)
        chromaInterleaved(cb, sums, count, shift, colour.cb, colour.cr);
    else if (step == 2 && cb == cr + 1)
        chromaInterleaved(cr, sums, count, shift, colour.cr, colour.cb);
    else if (step == 2)
        chromaLoop<2>(cb, cr, sums, count, shift, colour.cb, colour.cr);
    else if (cr == cb + 2)
        chromaPacked(cb, sums, count, shift, colour.cb, colour.cr);
    else if (cb == cr + 2)
        chromaPacked(cr, sums, count, shift, colour.cr, colour.cb);
    else
        chromaLoop<4>(cb, cr, sums, count, shift, colour.cb, colour.cr);
}

} // namespace overlayd
