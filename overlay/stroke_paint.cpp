// StrokeRasterizer's pixel loops: coverage across a stroke for a run of pixels (vector kernels for short and long
// runs) and the exact per-pixel formula beside the ends. The semantics are in stroke_raster.cpp's header comment.
#include "overlay/stroke_raster.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace overlayd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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

struct Across {
    float gain, reach; // the profile, in 0..255 units
    int peak;
    float s, ds; // signed distance across at the first pixel, and per pixel
};

// Long runs (a flat stroke's row): 16 pixels a step as four 4-lane float vectors holding pixels {0, 4, 8, 12} + j,
// so that or-ing the four results shifted by 0, 8, 16 and 24 bits puts the 16 bytes in pixel order (SSE2 has no
// cheap narrowing: GCC's own vectorization of this loop spent most of its time there and in integer clamps).
using Floats4 [[gnu::vector_size(16)]] = float;
using Ints4 [[gnu::vector_size(16)]] = int32_t;
using Longs2 [[gnu::vector_size(16)]] = uint64_t;
using Bytes16 [[gnu::vector_size(16)]] = uint8_t;

inline Floats4 across4(const Across &a, Floats4 lane, float n)
{
    const Floats4 x = a.s + lane * a.ds, distance = (Floats4)((Ints4)x & 0x7fffffff); // |x|: clear the sign bit
    Floats4 c = a.gain * (a.reach - distance);
    c = c > 0 ? c : 0;
    c = c < float(a.peak) ? c : float(a.peak);
    return lane < n ? c + 0.5f : 0;
}

template<bool Overwrite>
void paintLong(const Across &a, int n, uint8_t *out)
{
    static constexpr Floats4 kLane = {0, 4, 8, 12};
    for (int k = 0; k < n; k += kPad) {
        const Floats4 lane = kLane + float(k);
        Ints4 bytes = __builtin_convertvector(across4(a, lane, float(n)), Ints4);
        for (int j = 1; j < 4; ++j)
            bytes |= __builtin_convertvector(across4(a, lane + float(j), float(n)), Ints4) << (8 * j);
        Bytes16 v = (Bytes16)bytes;
        if (!Overwrite) {
            Bytes16 old;
            __builtin_memcpy(&old, out + k, sizeof old);
            v = old > v ? old : v;
        }
        __builtin_memcpy(out + k, &v, sizeof v);
    }
}

// Short runs (a steep stroke's 3 or 4 pixels a row, most runs): 4 lanes at a time in vector extensions, as in
// blend_kernel.cpp; a 16-pixel step would do 4 times the work. The four 32-bit results (each 0..255) become four
// bytes with two 64-bit shifts, and the max is one pmaxub: GCC turns a plain narrowing into scalar code.
template<bool Overwrite>
void paintShort(const Across &a, int n, uint8_t *out)
{
    static constexpr Floats4 kLane = {0, 1, 2, 3};
    for (int k = 0; k < n; k += 4) {
        Longs2 q = (Longs2) __builtin_convertvector(across4(a, kLane + float(k), float(n)), Ints4);
        q |= q >> 24; // lane bytes 0 and 4 of each half side by side
        uint32_t packed = uint32_t(q[0] & 0xffff) | uint32_t(q[1] << 16);
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
void paintAcross(const Across &a, int n, uint8_t *out)
{
    if (n <= 8)
        paintShort<Overwrite>(a, n, out);
    else
        paintLong<Overwrite>(a, n, out);
}

} // namespace

uint8_t StrokeRasterizer::coverage(const Segment &g, double t, double s) const
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

void StrokeRasterizer::paint(const Segment &g, int y, int x0, int count, uint8_t *out, bool overwrite) const
{
    const double dy = y - g.a.y, dx = x0 - g.a.x, dt = g.u.x, ds = -g.u.y;
    const double t = dy * g.u.y + dx * g.u.x, s = dy * g.u.x - dx * g.u.y;
    // [f0, f1): the pixels past neither a butt end's ramp nor a round end, where |s| alone decides; the few
    // others (and every pixel of a binary stroke) take the exact per-pixel formula.
    int f0 = 0, f1 = 0;
    if (!profile_.binary) {
        const double lo = g.roundStart ? 0.0 : profile_.extension;
        const double hi = g.roundEnd ? g.length : g.length - profile_.extension;
        const double tEnd = t + (count - 1) * dt;
        f1 = count; // the common case: the whole run lies between the ends
        if (std::min(t, tEnd) < lo || std::max(t, tEnd) > hi)
            std::tie(f0, f1) = indexRange(t, dt, lo, hi, count);
    }
    for (int k = 0; k < f0; ++k)
        out[k] =
            overwrite ? coverage(g, t + k * dt, s + k * ds) : std::max(out[k], coverage(g, t + k * dt, s + k * ds));
    const Across across{profile_.gain, float(profile_.reach), int(profile_.peak + 0.5f), float(s + f0 * ds), float(ds)};
    if (overwrite)
        paintAcross<true>(across, f1 - f0, out + f0);
    else
        paintAcross<false>(across, f1 - f0, out + f0);
    for (int k = f1; k < count; ++k)
        out[k] =
            overwrite ? coverage(g, t + k * dt, s + k * ds) : std::max(out[k], coverage(g, t + k * dt, s + k * ds));
}

} // namespace overlayd
