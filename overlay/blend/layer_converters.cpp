// SPDX-License-Identifier: Apache-2.0
// Per-layout conversion of the RGBA layer into native bytes. All format knowledge of the overlay lives here and runs
// once per (layer, format, colorimetry); the per-frame blend is format-blind.
#include "overlay/blend/layer_converters.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace overlayd {

namespace {

// Chroma groups [g0, g1) of one chroma row.
struct Interval {
    unsigned g0 = 0, g1 = 0;
};

// Scratch of one conversion, so that rows do not allocate.
struct Scratch {
    std::vector<Interval> raw, merged;
};

// Groups touched by any span of luma rows [y0, y1), merged: 4:2:0 chroma rows serve two luma rows, and rounding
// spans out to whole groups can make neighbouring spans overlap.
const std::vector<Interval> &groupIntervals(const OverlayLayer &layer, unsigned y0, unsigned y1, unsigned groupWidth,
                                            Scratch &scratch)
{
    std::vector<Interval> &raw = scratch.raw, &merged = scratch.merged;
    raw.clear();
    merged.clear();
    for (unsigned y = y0; y < y1; ++y) {
        for (const Span &span : layer.rowSpans(y))
            raw.push_back({span.x0 / groupWidth, (span.x1 + groupWidth - 1) / groupWidth});
    }
    if (y1 - y0 > 1) // one row's spans are already in order
        std::sort(raw.begin(), raw.end(), [](const Interval &a, const Interval &b) { return a.g0 < b.g0; });
    for (const Interval &next : raw) {
        if (!merged.empty() && next.g0 <= merged.back().g1)
            merged.back().g1 = std::max(merged.back().g1, next.g1);
        else
            merged.push_back(next);
    }
    return merged;
}

// Overlays are mostly runs of identical pixels (the inside of a line, a text box): remembering the last pixel
// (or macropixel) and its encoding skips most of the colour maths.
class LumaCache
{
public:
    explicit LumaCache(const YcbcrEncoder &encoder) : encoder_(encoder) {}
    BlendSample operator()(const uint8_t *rgba)
    {
        uint32_t key;
        std::memcpy(&key, rgba, 4);
        if (key != key_ || !valid_)
            key_ = key, value_ = encoder_.luma(rgba), valid_ = true;
        return value_;
    }

private:
    const YcbcrEncoder &encoder_;
    uint32_t key_ = 0;
    BlendSample value_{};
    bool valid_ = false;
};

// The chroma of a macropixel, keyed by its raw pixels so that a repeated macropixel costs a 16-byte compare.
class ChromaCache
{
public:
    explicit ChromaCache(const YcbcrEncoder &encoder) : encoder_(encoder) {}
    YcbcrBlendSamples operator()(const OverlayLayer &layer, unsigned group, const PixelFormatInfo &format,
                                 unsigned chromaRow)
    {
        // The macropixel's pixels that exist: a partial group at an odd right or bottom edge averages what is there.
        const unsigned x0 = group * format.hSubSampling, x1 = std::min(x0 + format.hSubSampling, layer.width());
        const unsigned y0 = chromaRow * format.vSubSampling, y1 = std::min(y0 + format.vSubSampling, layer.height());
        std::array<uint32_t, 4> key{};
        unsigned count = 0;
        for (unsigned y = y0; y < y1; ++y) {
            std::memcpy(&key[count], layer.pixel(x0, y), 4 * (x1 - x0));
            count += x1 - x0;
        }
        if (valid_ && count == count_ && key == key_)
            return value_;
        PremultipliedSum sum;
        for (unsigned i = 0; i < count; ++i)
            sum.add(reinterpret_cast<const uint8_t *>(&key[i]));
        key_ = key, count_ = count, value_ = encoder_.encode(sum), valid_ = true;
        return value_;
    }

private:
    const YcbcrEncoder &encoder_;
    std::array<uint32_t, 4> key_{};
    unsigned count_ = 0;
    YcbcrBlendSamples value_{};
    bool valid_ = false;
};

void convertLumaPlane(const OverlayLayer &layer, const PixelFormatInfo &, const YcbcrEncoder &encoder, NativeRuns &out)
{
    LumaCache luma(encoder);
    for (const Span &span : layer.spans()) {
        out.beginRun(0, span.y, span.x0);
        const uint8_t *px = layer.pixel(span.x0, span.y);
        for (unsigned x = span.x0; x < span.x1; ++x, px += 4)
            out.push(luma(px));
        out.endRun();
    }
}

void convertRgb(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &, NativeRuns &out)
{
    const unsigned bytes = format.planes[0].bytesPerGroup;
    for (const Span &span : layer.spans()) {
        out.beginRun(0, span.y, span.x0 * bytes);
        for (unsigned x = span.x0; x < span.x1; ++x) {
            const uint8_t *px = layer.pixel(x, span.y);
            std::array<BlendSample, 4> samples{}; // an X byte keeps alpha 0: left as it is
            samples[format.rOffset] = {px[0], px[3]};
            samples[format.gOffset] = {px[1], px[3]};
            samples[format.bOffset] = {px[2], px[3]};
            if (format.aOffset != kNoComponent)
                samples[format.aOffset] = {px[3], px[3]}; // alpha composes "over" like a colour
            for (unsigned k = 0; k < bytes; ++k)
                out.push(samples[k]);
        }
        out.endRun();
    }
}

void convertPacked422(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                      NativeRuns &out)
{
    Scratch scratch;
    LumaCache luma(encoder);
    ChromaCache encode(encoder);
    for (unsigned y = 0; y < layer.height(); ++y) {
        for (const Interval &interval : groupIntervals(layer, y, y + 1, 2, scratch)) {
            out.beginRun(0, y, interval.g0 * 4);
            for (unsigned g = interval.g0; g < interval.g1; ++g) {
                const YcbcrBlendSamples chroma = encode(layer, g, format, y);
                std::array<BlendSample, 4> samples{};
                samples[format.cbOffset] = chroma.cb;
                samples[format.crOffset] = chroma.cr;
                samples[format.yOffset[0]] = luma(layer.pixel(2 * g, y));
                if (2 * g + 1 < layer.width())
                    samples[format.yOffset[1]] = luma(layer.pixel(2 * g + 1, y));
                for (const BlendSample &sample : samples)
                    out.push(sample);
            }
            out.endRun();
        }
    }
}

// Each chroma row's covered group intervals with their groups' chroma encoded: the walk both 4:2:x layouts share.
template<typename EmitInterval>
void forChromaIntervals(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                        EmitInterval emit)
{
    Scratch scratch;
    ChromaCache encode(encoder);
    std::vector<YcbcrBlendSamples> chroma;
    for (unsigned row = 0; row < format.planeHeight(1, layer.height()); ++row) {
        const unsigned y0 = row * format.vSubSampling, y1 = std::min(y0 + format.vSubSampling, layer.height());
        for (const Interval &interval : groupIntervals(layer, y0, y1, format.hSubSampling, scratch)) {
            chroma.clear();
            for (unsigned g = interval.g0; g < interval.g1; ++g)
                chroma.push_back(encode(layer, g, format, row));
            emit(row, interval.g0, chroma);
        }
    }
}

void convertSemiPlanar(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                       NativeRuns &out)
{
    convertLumaPlane(layer, format, encoder, out);
    forChromaIntervals(layer, format, encoder,
                       [&](unsigned row, unsigned g0, const std::vector<YcbcrBlendSamples> &chroma) {
                           out.beginRun(1, row, g0 * 2);
                           for (const YcbcrBlendSamples &group : chroma) {
                               std::array<BlendSample, 2> samples{};
                               samples[format.cbOffset] = group.cb;
                               samples[format.crOffset] = group.cr;
                               out.push(samples[0]);
                               out.push(samples[1]);
                           }
                           out.endRun();
                       });
}

void convertPlanar(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                   NativeRuns &out)
{
    convertLumaPlane(layer, format, encoder, out);
    forChromaIntervals(layer, format, encoder,
                       [&](unsigned row, unsigned g0, const std::vector<YcbcrBlendSamples> &chroma) {
                           out.beginRun(format.cbPlane, row, g0);
                           for (const YcbcrBlendSamples &samples : chroma)
                               out.push(samples.cb);
                           out.endRun();
                           out.beginRun(format.crPlane, row, g0);
                           for (const YcbcrBlendSamples &samples : chroma)
                               out.push(samples.cr);
                           out.endRun();
                       });
}

// Indexed by PixelLayout.
constexpr LayerConverter kConverters[] = {
    convertPacked422,  // PackedYuv422
    convertSemiPlanar, // SemiPlanar
    convertPlanar,     // Planar
    convertRgb,        // PackedRgb
    convertLumaPlane,  // Grey
};

} // namespace

LayerConverter layerConverter(PixelLayout layout)
{
    return kConverters[static_cast<unsigned>(layout)];
}

} // namespace overlayd
