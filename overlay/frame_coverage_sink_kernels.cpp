// FrameCoverageSink's row paths and pixel loops (packed 4:2:2, luma with planar or semi-planar chroma, RGB): the
// premultiplied "over" of blend_kernel.cpp with the value and 255 - alpha computed from the opacity on the fly, in
// 16-bit lanes (built with -O3).
#include "overlay/frame_coverage_sink.h"

#include "overlay/div255.h"
#include "overlay/sink_lanes.h"

#include <algorithm>
#include <cassert>

namespace overlayd {

using namespace sink_lanes;

namespace {

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

// lumaShort for up to 8 one-byte luma samples (planar and semi-planar formats, GREY): half the lanes.
inline void lumaEight(uint8_t *pixels, const uint8_t *alpha, unsigned value)
{
    Bytes16 a{}, in{};
    __builtin_memcpy(&a, alpha, 8);
    __builtin_memcpy(&in, pixels, 8);
    const Words8 a8 = lowWords(a);
    const Words8 out = div255(Words8(a8 * uint16_t(value))) + div255(Words8(lowWords(in) * (255 - a8)));
    const Bytes8 packed = __builtin_convertvector(out, Bytes8);
    __builtin_memcpy(pixels, &packed, 8);
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

} // namespace

// Each 16-bit word of packed 4:2:2 is one pixel's luma byte and one chroma byte of its macropixel (YUYV: Y0 Cb,
// Y1 Cr, ...), so a window splits into eight luma lanes and eight chroma lanes by shifts. Luma takes over()'s rule,
// chroma chromaLoop's with the macropixel's two opacities summed (shift 1): byte for byte the two-pass result.
[[gnu::always_inline]] inline void FrameCoverageSink::blendPackedWindows(uint8_t *bytes, const uint8_t *alpha,
                                                                         unsigned windows, const ItemColour &colour,
                                                                         unsigned lumaOffset)
{
    Words8 chromaCode;
    __builtin_memcpy(&chromaCode, colour.packedChroma, 16);
    const uint16_t luma = uint16_t(colour.luma);
    const unsigned lumaShift = 8 * lumaOffset, chromaShift = 8 - lumaShift;
    for (unsigned w = 0; w < windows; ++w, bytes += 16, alpha += 8) {
        Bytes16 raw{};
        __builtin_memcpy(&raw, alpha, 8);
        const Words8 a = lowWords(raw);
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
}

void FrameCoverageSink::blendPackedRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    // Whole windows of four macropixels from the run's first, as long as they end inside the row and before a
    // one-pixel macropixel at an odd right edge; the groups past the last window go the general way.
    const unsigned g0 = unsigned(x0) / 2, gEnd = unsigned(x0 + count + 1) / 2, wholeGroups = frame_.width / 2;
    const unsigned windows = std::min((gEnd - g0 + 3) / 4, (wholeGroups - std::min(g0, wholeGroups)) / 4);
    blendPackedWindows(row + size_t(g0) * 4, alpha - x0 % 2, windows, colour_, layout_.lumaOffset);
    const int rest = std::max(x0, int(2 * (g0 + 4 * windows)));
    if (rest >= x0 + count)
        return;
    const int done = rest - x0;
    blendLuma(row + size_t(rest) * 2, layout_, alpha + done, unsigned(count - done), colour_.luma,
              rowBytes_ - size_t(rest) * 2);
    accumulateAlpha(alphaSums_.data(), unsigned(rest), alpha + done, unsigned(count - done));
    blendChromaInterval(unsigned(y), {unsigned(rest) / 2, gEnd});
}

void FrameCoverageSink::accumulateAlpha(uint16_t *sums, unsigned x0, const uint8_t *alpha, unsigned count)
{
    // Sixteen pixels (eight groups) a step from the first group's first pixel: alpha is staged, so the pixel before
    // an odd x0 and the 16 after the last read 0, and sums has slack for the eight groups past the last.
    const uint8_t *pixels = alpha - x0 % 2;
    uint16_t *group = sums + x0 / 2;
    for (unsigned i = 0; i < x0 % 2 + count; i += 16, pixels += 16, group += 8) {
        Words8 pairs, sum;
        __builtin_memcpy(&pairs, pixels, 16);
        __builtin_memcpy(&sum, group, 16);
        sum += (pairs & 0xff) + (pairs >> 8);
        __builtin_memcpy(group, &sum, 16);
    }
}

// Luma (or GREY) and planar or semi-planar chroma of one row() call.
void FrameCoverageSink::blendYuvRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    const size_t start = size_t(x0) * layout_.lumaStep;
    if (layout_.lumaStep == 1 && count <= 8 && rowBytes_ - start >= 8) // the usual thin-line run: 8 lanes, inline
        lumaEight(row + start, alpha, colour_.luma);
    else
        blendLuma(row + start, layout_, alpha, unsigned(count), colour_.luma, rowBytes_ - start);
    if (!layout_.chroma)
        return;
    // A chroma row's opacities add up in alphaSums_ until its last luma row: the first row's groups wait in
    // intervals_, the last row's are blended as they come, with the waiting ones beside them.
    const int chromaRow = y >> (layout_.vSub - 1); // vSub is 1 or 2: no division per call
    if (chromaRow != pendingChromaRow_)
        flushChroma();
    accumulateAlpha(alphaSums_.data(), unsigned(x0), alpha, unsigned(count));
    const Interval groups{unsigned(x0) / 2, unsigned(x0 + count + 1) / 2};
    if (((y + 1) & int(layout_.vSub - 1)) == 0 || unsigned(y + 1) == frame_.height) {
        blendLastRowGroups(unsigned(chromaRow), groups);
        return;
    }
    pendingChromaRow_ = chromaRow;
    intervals_.push_back(groups);
}

void FrameCoverageSink::blendLuma(uint8_t *pixels, const Layout &layout, const uint8_t *alpha, unsigned count,
                                  unsigned value, size_t room)
{
    const unsigned step = layout.lumaStep;
    assert(step == 1 || step == 2);
    // A long run (a flat line near the camera) as whole 16-byte vectors too, then its remainder.
    const unsigned perVector = 16 / step;
    while (count > perVector && room >= 32) {
        lumaShort(pixels, step, layout.lumaOffset, alpha, value);
        pixels += 16, room -= 16, alpha += perVector, count -= perVector;
    }
    if (count * step <= 16 && room >= 16)
        return lumaShort(pixels, step, layout.lumaOffset, alpha, value);
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

} // namespace overlayd
