// SPDX-License-Identifier: Apache-2.0
// StrokeRowPainter: merging a row's runs, coverage across a stroke for a run of pixels (vector kernels for short and
// long runs, the exact per-pixel formula beside the ends) and trimming before the sink. The semantics are in
// stroke_raster.cpp's header comment.
#include "overlay/raster/stroke_row_painter.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace overlayd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxWidth = 1e6;

// The indices k in [0, n) with lo <= t0 + k * dt <= hi, as [first, last).
std::pair<int, int> indexRange(double t0, double dt, double lo, double hi, int n)
{
    double k0 = -kInf, k1 = kInf;
    if (dt > 0) {
        k0 = (lo - t0) / dt, k1 = (hi - t0) / dt;
    } else if (dt < 0) {
        k0 = (hi - t0) / dt, k1 = (lo - t0) / dt;
    } else if (t0 < lo || t0 > hi) {
        return {0, 0};
    }
    const double first = std::clamp(std::ceil(k0), 0.0, double(n));
    const double last = std::clamp(std::floor(k1) + 1.0, first, double(n));
    return {int(first), int(last)};
}

// Between the ends, away from butt ends' ramps, coverage depends on the distance across alone: no square root, no
// branch per pixel. Lanes past n get 0; the row scratch has kPad bytes of slack for them. A run no other run
// overlaps is written rather than max-ed into a zeroed scratch.
constexpr int kPad = kStrokeRowSlack;
// The byte packing below and the trimming read bytes from the low bits of a word (x86-64, arm64).
static_assert(std::endian::native == std::endian::little, "little-endian words assumed");

// Vector extensions (GCC and Clang), as in blend_kernel.cpp.
using Floats4 [[gnu::vector_size(16)]] = float;
using Ints4 [[gnu::vector_size(16)]] = int32_t;
using Longs2 [[gnu::vector_size(16)]] = uint64_t;
using Bytes16 [[gnu::vector_size(16)]] = uint8_t;

// The profile's lanes and the signed distance across at the run's first pixel and its step per pixel.
struct Across {
    Floats4 negGain, reach, peak, half, s, ds;
};

// The coverage (plus 0.5, to be truncated) of the pixels whose lane * ds is given: clamp(gain * (reach - |x|), 0,
// peak) computed as -gain * (|x| - reach), the same number (negation is exact; a zero's sign goes with the clamp),
// which SSE2's two-operand instructions take without copies.
inline Floats4 acrossSteps(const Across &a, Floats4 laneTimesDs)
{
    const Floats4 x = a.s + laneTimesDs, distance = (Floats4)((Ints4)x & 0x7fffffff); // |x|: clear the sign bit
    Floats4 c = a.negGain * (distance - a.reach);
    c = c > 0 ? c : 0;
    c = c < a.peak ? c : a.peak;
    return c + a.half;
}

// acrossSteps of the pixels `lane`; when Masked, lanes at or past n get 0.
template<bool Masked>
inline Floats4 across4(const Across &a, Floats4 lane, float n)
{
    const Floats4 c = acrossSteps(a, lane * a.ds);
    if constexpr (Masked)
        return lane < n ? c : 0;
    else
        return c;
}

// Four 32-bit lanes (each 0..255) as four bytes in a word: bytes 0 and 4 of each half side by side (two 64-bit
// shifts), then the high half's pair next to the low's (a 6-byte shift): GCC turns a plain narrowing into scalar
// code.
inline uint32_t packBytes(Ints4 lanes)
{
    Longs2 q = (Longs2)lanes;
    q |= q >> 24;
    const Bytes16 b = (Bytes16)q;
    const Bytes16 high =
        __builtin_shufflevector(b, Bytes16{}, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21);
    return uint32_t(((Ints4)(b | high))[0]);
}

// Long runs (a flat stroke's row): 16 pixels a step as four 4-lane float vectors holding pixels {0, 4, 8, 12} + j,
// so that or-ing the four results shifted by 0, 8, 16 and 24 bits puts the 16 bytes in pixel order (SSE2 has no
// cheap narrowing: GCC's own vectorization of this loop spent most of its time there and in integer clamps). Only
// the last step needs the lane mask.
template<bool Overwrite, bool Masked>
inline void paint16(const Across &a, int k, int n, uint8_t *out)
{
    static constexpr Floats4 kLane = {0, 4, 8, 12};
    const Floats4 lane = kLane + float(k);
    Ints4 bytes = __builtin_convertvector(across4<Masked>(a, lane, float(n)), Ints4);
    for (int j = 1; j < 4; ++j)
        bytes |= __builtin_convertvector(across4<Masked>(a, lane + float(j), float(n)), Ints4) << (8 * j);
    Bytes16 v = (Bytes16)bytes;
    if (!Overwrite) {
        Bytes16 old;
        __builtin_memcpy(&old, out + k, sizeof old);
        v = old > v ? old : v;
    }
    __builtin_memcpy(out + k, &v, sizeof v);
}

template<bool Overwrite>
void paintLong(const Across &a, int n, uint8_t *out)
{
    int k = 0;
    for (; k + kPad <= n; k += kPad)
        paint16<Overwrite, false>(a, k, n, out);
    if (k < n)
        paint16<Overwrite, true>(a, k, n, out);
}

// Short runs (a steep stroke's 3 or 4 pixels a row, most runs): 4 lanes at a time in vector extensions, as in
// blend_kernel.cpp; a 16-pixel step would do 4 times the work. The max is one pmaxub.
template<bool Overwrite>
void paintShort(const Across &a, int n, uint8_t *out)
{
    static constexpr Floats4 kLane = {0, 1, 2, 3};
    for (int k = 0; k < n; k += 4) {
        uint32_t packed = packBytes(__builtin_convertvector(across4<true>(a, kLane + float(k), float(n)), Ints4));
        if (!Overwrite) {
            uint32_t old;
            __builtin_memcpy(&old, out + k, sizeof old);
            const Bytes16 p = (Bytes16)Ints4{int32_t(packed), 0, 0, 0}, o = (Bytes16)Ints4{int32_t(old), 0, 0, 0};
            packed = uint32_t(((Ints4)(p > o ? p : o))[0]);
        }
        __builtin_memcpy(out + k, &packed, sizeof packed);
    }
}

template<bool Overwrite>
void paintAcross(const Across &across, int n, uint8_t *out)
{
    // A local copy: the byte stores could alias the caller's, which would be reloaded at every step.
    const Across a = across;
    if (n <= 8)
        paintShort<Overwrite>(a, n, out);
    else
        paintLong<Overwrite>(a, n, out);
}

// The trimming of a run's zero ends, 8 bytes at a time: a byte loop's exit branch is mispredicted about once a run.
// Reads up to 7 bytes past p + n (the scratch's slack), never before p.

uint64_t word(const uint8_t *p, int valid)
{
    uint64_t w;
    __builtin_memcpy(&w, p, sizeof w);
    return valid >= 8 ? w : w & ((uint64_t(1) << (8 * valid)) - 1);
}

// The first non-zero byte of p[0, n), or n.
int firstNonZero(const uint8_t *p, int n)
{
    for (int i = 0; i < n; i += 8)
        if (const uint64_t w = word(p + i, n - i))
            return i + std::countr_zero(w) / 8;
    return n;
}

// One past the last non-zero byte of p[0, n) (p[0, n) has one).
int endNonZero(const uint8_t *p, int n)
{
    for (int e = n; e > 0; e -= 8) {
        const uint64_t w = e >= 8 ? word(p + e - 8, 8) : word(p, e) << (8 * (8 - e));
        if (w)
            return e - std::countl_zero(w) / 8;
    }
    return 0;
}

} // namespace

void StrokeRowPainter::setStroke(double width, bool antialias, const LayerRect &clip)
{
    // Wider than any frame is as wide as one: 255 * reach must stay far from the int range of the kernels.
    const double hw = 0.5 * std::min(width, kMaxWidth);
    if (!antialias)
        profile_ = {255.0f, 255.0f, std::max(hw, 0.5), 0.0, true};
    else if (width < 1.0)
        profile_ = {float(255.0 * width), float(255.0 * width), 1.0, 0.5, false};
    else
        profile_ = {255.0f, 255.0f, hw + 0.5, 0.5, false};
    profile_.negGainLanes = -profile_.gain + Floats4{};
    profile_.halfLanes = 0.5f + Floats4{};
    profile_.reachLanes = float(profile_.reach) + Floats4{};
    profile_.peakLanes = float(int(profile_.peak + 0.5f)) + Floats4{};
    clip_ = clip;
}

void StrokeRowPainter::reserve(size_t segments)
{
    row_.resize(std::max(row_.size(), size_t(int64_t(clip_.x1) - clip_.x0 + kStrokeRowSlack)));
    rowRuns_.resize(std::max(rowRuns_.size(), segments));
}

uint8_t StrokeRowPainter::coverage(const Segment &g, double t, double s) const
{
    const double past = t - std::clamp(t, g.roundStart ? 0.0 : -kInf, g.roundEnd ? g.length : kInf);
    const double d = past == 0.0 ? std::fabs(s) : std::sqrt(past * past + s * s);
    if (profile_.binary) {
        const bool cut = (!g.roundStart && t < 0.0) || (!g.roundEnd && t > g.length);
        return !cut && d <= profile_.reach ? 255 : 0;
    }
    double c = std::clamp(profile_.gain * (profile_.reach - d), 0.0, double(profile_.peak));
    if (!g.roundStart)
        c *= std::clamp(profile_.extension + t, 0.0, 1.0);
    if (!g.roundEnd)
        c *= std::clamp(profile_.extension + g.length - t, 0.0, 1.0);
    return uint8_t(c + 0.5);
}

void StrokeRowPainter::paint(const Segment &g, int y, int x0, int count, uint8_t *out, bool overwrite) const
{
    const double dy = y - g.a.y, dx = x0 - g.a.x, dt = g.u.x, ds = -g.u.y;
    const double t = dy * g.u.y + dx * g.u.x, s = dy * g.u.x - dx * g.u.y;
    // [f0, f1): the pixels past neither a butt end's ramp nor a round end, where |s| alone decides; the few
    // others (and every pixel of a binary stroke) take the exact per-pixel formula.
    int f0 = 0, f1 = 0;
    if (!profile_.binary) {
        const double tEnd = t + (count - 1) * dt;
        f1 = count; // the common case: the whole run lies between the ends
        if (std::min(t, tEnd) < g.innerLo || std::max(t, tEnd) > g.innerHi)
            std::tie(f0, f1) = indexRange(t, dt, g.innerLo, g.innerHi, count);
    }
    for (int k = 0; k < f0; ++k)
        out[k] =
            overwrite ? coverage(g, t + k * dt, s + k * ds) : std::max(out[k], coverage(g, t + k * dt, s + k * ds));
    const Across across{profile_.negGainLanes,
                        profile_.reachLanes,
                        profile_.peakLanes,
                        profile_.halfLanes,
                        float(s + f0 * ds) + Floats4{},
                        g.dsLanes};
    if (overwrite)
        paintAcross<true>(across, f1 - f0, out + f0);
    else
        paintAcross<false>(across, f1 - f0, out + f0);
    for (int k = f1; k < count; ++k)
        out[k] =
            overwrite ? coverage(g, t + k * dt, s + k * ds) : std::max(out[k], coverage(g, t + k * dt, s + k * ds));
}

void StrokeRowPainter::emitRow(int y, const Span *spans, size_t count, CoverageSink &sink)
{
    // Runs are painted in x order and a paint writes only from its own x0 on, so a run's bytes stay as painted
    // until the row is handed over (the short kernel's extra lanes land where later runs paint). The row scratch
    // has kStrokeRowSlack bytes past the clip's last pixel, so every run is readable that far past its end.
    uint8_t *const scratch = row_.data();
    const int clipX0 = clip_.x0;
    CoverageRun *const runs = rowRuns_.data(), *out = runs;
    Across across{profile_.negGainLanes, profile_.reachLanes, profile_.peakLanes, profile_.halfLanes, {}, {}};
    const Span *const end = spans + count;
    for (const Span *span = spans; span < end;) {
        // spans[count] is idle (kIdle), so the next span can be read without a bound check.
        const Span *next = span + 1;
        if (next->x0 <= span->x1 + 1) {
            // Overlapping or touching runs share one scratch run (max per pixel) and one sink run.
            int x1 = span->x1;
            for (; next < end && next->x0 <= x1 + 1; ++next)
                x1 = std::max(x1, next->x1);
            out = addMerged(y, span, size_t(next - span), span->x0, x1, out);
            span = next;
            continue;
        }
        const int x0 = span->x0, n = span->x1 - x0 + 1;
        uint8_t *const row = scratch + (x0 - clipX0);
        if (span->fast) {
            // paint(overwrite)'s short kernel, inlined: 4 lanes (or 8) and no lane mask, as pixels past the run are
            // never read (a later run overwrites or zeroes its own pixels first). s + 0 * ds is s but for the sign
            // of a zero, which |x| drops; lane * ds comes from the segment, the same product.
            const float s0 = span->s0;
            across.s = Floats4{s0, s0, s0, s0};
            const Floats4 *const steps = span->segment->laneSteps;
            const uint32_t low = packBytes(__builtin_convertvector(acrossSteps(across, steps[0]), Ints4));
            __builtin_memcpy(row, &low, sizeof low);
            if (n > 4) {
                const uint32_t high = packBytes(__builtin_convertvector(acrossSteps(across, steps[1]), Ints4));
                __builtin_memcpy(row + 4, &high, sizeof high);
            }
        } else {
            paint(*span->segment, y, x0, n, row, true);
        }
        if (row[0] != 0 && row[n - 1] != 0) { // the usual case: a run's end pixels are covered
            out->x0 = x0, out->count = n, out->coverage = row;
            ++out;
        } else {
            out = addTrimmed(x0, row, n, out);
        }
        span = next;
    }
    if (out != runs)
        sink.rowRuns(y, runs, size_t(out - runs));
}

CoverageRun *StrokeRowPainter::addMerged(int y, const Span *spans, size_t count, int x0, int x1, CoverageRun *out)
{
    uint8_t *const row = row_.data() + (x0 - clip_.x0);
    const int n = x1 - x0 + 1;
    std::fill(row, row + n, uint8_t(0));
    for (size_t i = 0; i < count; ++i)
        paint(*spans[i].segment, y, spans[i].x0, spans[i].x1 - spans[i].x0 + 1, row + (spans[i].x0 - x0), false);
    if (row[0] != 0 && row[n - 1] != 0)
        *out++ = {x0, n, row};
    else
        out = addTrimmed(x0, row, n, out);
    return out;
}

CoverageRun *StrokeRowPainter::addTrimmed(int x0, const uint8_t *row, int n, CoverageRun *out)
{
    const int first = firstNonZero(row, n);
    if (first < n)
        *out++ = {x0 + first, endNonZero(row, n) - first, row + first};
    return out;
}

} // namespace overlayd
