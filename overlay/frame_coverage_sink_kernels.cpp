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
// two-pass result. a: the opacities of the window's eight pixels.
// packedChroma: the chroma lanes' codes at full opacity.
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

} // namespace

void FrameCoverageSink::blendPackedRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    // Whole windows of four macropixels from the run's first, as long as they end inside the row and before a
    // one-pixel macropixel at an odd right edge; the groups past the last window go the general way.
    const unsigned g0 = unsigned(x0) / 2, gEnd = unsigned(x0 + count + 1) / 2, wholeGroups = frame_.width / 2;
    const unsigned windows = std::min((gEnd - g0 + 3) / 4, (wholeGroups - std::min(g0, wholeGroups)) / 4);
    const uint8_t *pixels = alpha - x0 % 2; // staged: the pixel before an odd x0 reads 0
    for (unsigned w = 0; w < windows; ++w, pixels += 8)
        blendPackedWindow(row + size_t(g0 + 4 * w) * 4, eightOpacities(pixels), colour_.packedChroma, colour_.luma,
                          layout_.lumaOffset);
    const int rest = std::max(x0, int(2 * (g0 + 4 * windows)));
    if (rest >= x0 + count)
        return;
    const int done = rest - x0;
    blendLuma(row + size_t(rest) * 2, layout_, alpha + done, unsigned(count - done), colour_.luma,
              rowBytes_ - size_t(rest) * 2);
    accumulateAlpha(alphaSums_.data(), unsigned(rest), alpha + done, unsigned(count - done));
    blendChromaRange(unsigned(y), {unsigned(rest) / 2, gEnd});
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

inline int FrameCoverageSink::enterChromaRow(int y)
{
    const int chromaRow = y >> (layout_.vSub - 1); // vSub is 1 or 2: no division per call
    if (chromaRow != pendingChromaRow_)
        flushChroma();
    return chromaRow;
}

// A chroma row's opacities add up in alphaSums_ until its last luma row: the first row's groups wait in intervals_,
// the last row's are blended as they come, with the waiting ones beside them.
inline void FrameCoverageSink::addChromaGroups(int y, int chromaRow, Interval groups)
{
    if (((y + 1) & int(layout_.vSub - 1)) == 0 || unsigned(y + 1) == frame_.height) {
        blendLastRowGroups(unsigned(chromaRow), groups);
        return;
    }
    pendingChromaRow_ = chromaRow;
    intervals_.push_back(groups);
}

bool FrameCoverageSink::blendShortPacked(uint8_t *row, const CoverageRun &run) const
{
    // One window from the run's first macropixel, if the run fits in it and its four macropixels are whole ones
    // of the row.
    const unsigned x0 = unsigned(run.x0), count = unsigned(run.count), parity = x0 % 2, g0 = x0 / 2;
    if (parity + count > 8 || g0 + 4 > frame_.width / 2)
        return false;
    const uint64_t coverage = shortCoverage(run.coverage, count) << (8 * parity);
    blendPackedWindow(row + size_t(g0) * 4, wordLanes(opacities(coverage, colour_.alpha)), colour_.packedChroma,
                      colour_.luma, layout_.lumaOffset);
    return true;
}

bool FrameCoverageSink::blendShortYuv(uint8_t *row, int y, const CoverageRun &run)
{
    const unsigned x0 = unsigned(run.x0), count = unsigned(run.count), parity = x0 % 2;
    if (parity + count > 8 || !layout_.byteLuma || rowBytes_ - x0 < 8)
        return false;
    const uint64_t alpha = opacities(shortCoverage(run.coverage, count), colour_.alpha);
    lumaEight(row + x0, wordLanes(alpha), colour_.luma);
    if (!layout_.chroma)
        return true;
    const int chromaRow = enterChromaRow(y);
    // The run's (at most four) groups' opacity sums, added in one step: a 16-bit word of the bytes from the first
    // group's first pixel holds one group's two opacities.
    const Words8 pairs = (Words8)Longs2{alpha << (8 * parity), 0};
    uint16_t *const group = alphaSums_.data() + x0 / 2;
    Words8 sum;
    __builtin_memcpy(&sum, group, 16);
    sum += (pairs & 0xff) + (pairs >> 8);
    __builtin_memcpy(group, &sum, 16);
    addChromaGroups(y, chromaRow, {x0 / 2, (x0 + count + 1) / 2});
    return true;
}

// Luma (or GREY) and planar or semi-planar chroma of one row() call.
void FrameCoverageSink::blendYuvRow(uint8_t *row, int y, int x0, const uint8_t *alpha, int count)
{
    const size_t start = size_t(x0) * layout_.lumaStep;
    if (layout_.lumaStep == 1 && count <= 8 && rowBytes_ - start >= 8) // the usual thin-line run: 8 lanes, inline
        lumaEight(row + start, eightOpacities(alpha), colour_.luma);
    else
        blendLuma(row + start, layout_, alpha, unsigned(count), colour_.luma, rowBytes_ - start);
    if (!layout_.chroma)
        return;
    const int chromaRow = enterChromaRow(y);
    accumulateAlpha(alphaSums_.data(), unsigned(x0), alpha, unsigned(count));
    addChromaGroups(y, chromaRow, {unsigned(x0) / 2, unsigned(x0 + count + 1) / 2});
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
