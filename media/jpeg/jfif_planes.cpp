// SPDX-License-Identifier: Apache-2.0
// JfifPlanes: the table entry says where each component's samples sit; the loops below only step through them.
// This runs on every frame of an MJPEG stream, so the steps of the table's layouts (1, 2 and 4 bytes) are compile-time
// constants in the sample loops and every conversion is a table read.
#include "media/jpeg/jfif_planes.h"

#include <algorithm>
#include <string>
#include <type_traits>

namespace overlayd {

namespace {

// One component's samples: sample i of row r at base[r * stride + i * step].
struct Samples {
    const uint8_t *base = nullptr;
    size_t stride = 0;
    unsigned step = 1;

    const uint8_t *row(unsigned r) const { return base + r * stride; }
};

struct FrameSamples {
    Samples y, cb, cr;
    unsigned width = 0, height = 0;
    unsigned chromaWidth = 0, chromaHeight = 0, hSub = 1, vSub = 1;
    bool hasChroma = false;
    unsigned lumaOutStride = 0; // the luma scratch plane's row length (the width padded to whole chroma sites)
};

// Luma steps by plane 0's bytes per pixel (both of a group's Y bytes must follow that step); chroma by its plane's
// bytes per group, which holds exactly one chroma sample when a group is one chroma site wide.
Result<FrameSamples> locate(const FrameView &frame)
{
    const PixelFormatInfo &f = *frame.format;
    const unsigned lumaStep = f.planes[0].bytesPerGroup / f.pixelsPerGroup;
    const bool hasChroma = f.cbOffset != kNoComponent;
    const bool evenLuma = f.yOffset[1] == kNoComponent || f.yOffset[1] == f.yOffset[0] + lumaStep;
    if (f.encoding != ColourEncoding::Yuv || lumaStep == 0 || !evenLuma ||
        (hasChroma && f.pixelsPerGroup != f.hSubSampling))
        return makeError(ErrorCode::Unsupported, "JPEG encoder: no sample layout for " + std::string(f.name));
    FrameSamples s;
    s.width = frame.width, s.height = frame.height, s.hasChroma = hasChroma;
    s.y = {frame.planes[0].data + f.yOffset[0], frame.planes[0].stride, lumaStep};
    if (!hasChroma)
        return s;
    s.hSub = f.hSubSampling, s.vSub = f.vSubSampling;
    s.chromaWidth = (frame.width + s.hSub - 1) / s.hSub;
    s.chromaHeight = (frame.height + s.vSub - 1) / s.vSub;
    const PlaneView &cb = frame.planes[f.cbPlane], &cr = frame.planes[f.crPlane];
    s.cb = {cb.data + f.cbOffset, cb.stride, f.planes[f.cbPlane].bytesPerGroup};
    s.cr = {cr.data + f.crOffset, cr.stride, f.planes[f.crPlane].bytesPerGroup};
    return s;
}

// Calls body with the step as a compile-time constant for the steps the table uses, so that the sample loops
// compile to fixed-stride loads; any other step still works, at run-time stride.
template<typename Body>
void withStep(unsigned step, Body body)
{
    switch (step) {
    case 1:
        return body(std::integral_constant<unsigned, 1>{});
    case 2:
        return body(std::integral_constant<unsigned, 2>{});
    case 4:
        return body(std::integral_constant<unsigned, 4>{});
    default:
        return body(step);
    }
}

// One row of one component through a per-sample table (range expansion; the identity for full range).
void mapRow(const uint8_t *src, unsigned step, uint8_t *dst, unsigned count, const uint8_t *table)
{
    // By value: byte stores may alias anything, so captured references would be reloaded on every sample.
    withStep(step, [=](auto constantStep) {
        for (unsigned i = 0; i < count; ++i)
            dst[i] = table[src[i * constantStep]];
    });
}

// All components through the per-sample tables, in one pass down the frame (each chroma row, then the luma rows
// that share it) so that a packed frame is read from memory once, not once per component.
void convertRange(const FrameSamples &s, const JfifMapping &m, const std::array<uint8_t *, 3> &out)
{
    const uint8_t *lumaTable = m.lumaTable(), *chromaTable = m.chromaTable();
    for (unsigned y = 0; y < s.height; ++y) {
        if (s.hasChroma && y % s.vSub == 0) {
            const unsigned cy = y / s.vSub;
            if (out[1])
                mapRow(s.cb.row(cy), s.cb.step, out[1] + size_t(cy) * s.chromaWidth, s.chromaWidth, chromaTable);
            if (out[2])
                mapRow(s.cr.row(cy), s.cr.step, out[2] + size_t(cy) * s.chromaWidth, s.chromaWidth, chromaTable);
        }
        if (out[0])
            mapRow(s.y.row(y), s.y.step, out[0] + size_t(y) * s.lumaOutStride, s.width, lumaTable);
    }
}

// One chroma row through the matrix, and the luma offset of each of its sites. Arguments by value, as for
// matrixLumaRow.
template<typename Step>
void matrixChromaRow(const uint8_t *cb, const uint8_t *cr, Step step, uint8_t *cbOut, uint8_t *crOut, int32_t *offsets,
                     unsigned count, const JfifMapping &m)
{
    for (unsigned c = 0; c < count; ++c) {
        const uint8_t b = cb[c * step], r = cr[c * step];
        cbOut[c] = m.cb(b, r), crOut[c] = m.cr(b, r), offsets[c] = m.lumaOffset(b, r);
    }
}

// One luma row through the matrix, each pixel with its chroma site's offset. The row's sizes and pointers are
// locals so that the byte stores (which may alias anything) do not force them to be reloaded; 2-pixel sites, the
// only width in the table, get a loop without the inner bound.
template<typename Step>
void matrixLumaRow(const uint8_t *src, Step step, uint8_t *dst, unsigned width, unsigned hSub, const int32_t *offsets,
                   const JfifMapping &m)
{
    if (hSub != 2) {
        for (unsigned x = 0; x < width; ++x)
            dst[x] = m.luma(src[x * step], offsets[x / hSub]);
        return;
    }
    unsigned x = 0;
    for (; x + 1 < width; x += 2) {
        const int32_t offset = offsets[x / 2];
        dst[x] = m.luma(src[x * step], offset);
        dst[x + 1] = m.luma(src[(x + 1) * step], offset);
    }
    if (x < width)
        dst[x] = m.luma(src[x * step], offsets[x / 2]);
}

// All three components through the matrix: each chroma row first (its samples and its sites' luma offsets), then
// the luma rows that share it.
void convertMatrix(const FrameSamples &s, const JfifMapping &m, const std::array<uint8_t *, 3> &out,
                   std::vector<int32_t> &offsetRow)
{
    offsetRow.resize(s.chromaWidth);
    int32_t *offsets = offsetRow.data();
    const unsigned chromaWidth = s.chromaWidth;
    for (unsigned cy = 0; cy < s.chromaHeight; ++cy) {
        uint8_t *cbOut = out[1] + size_t(cy) * chromaWidth, *crOut = out[2] + size_t(cy) * chromaWidth;
        const uint8_t *cb = s.cb.row(cy), *cr = s.cr.row(cy);
        withStep(s.cb.step, [&](auto step) { matrixChromaRow(cb, cr, step, cbOut, crOut, offsets, chromaWidth, m); });
        const unsigned lastRow = std::min((cy + 1) * s.vSub, s.height);
        withStep(s.y.step, [&](auto step) {
            for (unsigned y = cy * s.vSub; y < lastRow; ++y)
                matrixLumaRow(s.y.row(y), step, out[0] + size_t(y) * s.lumaOutStride, s.width, s.hSub, offsets, m);
        });
    }
}

// Repeats the last column and row of a width x height plane into its padding up to paddedWidth x paddedHeight.
void padPlane(uint8_t *plane, unsigned width, unsigned height, unsigned paddedWidth, unsigned paddedHeight)
{
    for (unsigned y = 0; y < height && paddedWidth > width; ++y) {
        uint8_t *row = plane + size_t(y) * paddedWidth;
        std::fill(row + width, row + paddedWidth, row[width - 1]);
    }
    for (unsigned y = height; y < paddedHeight; ++y)
        std::copy_n(plane + size_t(height - 1) * paddedWidth, paddedWidth, plane + size_t(y) * paddedWidth);
}

} // namespace

Status JfifPlanes::gather(const FrameView &frame, const JfifMapping &mapping)
{
    auto located = locate(frame);
    if (!located)
        return located.error();
    FrameSamples &s = *located;
    // tjCompressFromYUVPlanes reads luma up to whole chroma sites (an odd-sized 4:2:0 frame: one more column and
    // row than it has): such a frame's luma is copied into a plane with that padding, its edge samples repeated.
    const unsigned paddedWidth = (s.width + s.hSub - 1) / s.hSub * s.hSub;
    const unsigned paddedHeight = (s.height + s.vSub - 1) / s.vSub * s.vSub;
    const bool lumaPadded = paddedWidth != s.width || paddedHeight != s.height;
    s.lumaOutStride = paddedWidth;
    const std::array<const Samples *, 3> in{&s.y, &s.cb, &s.cr};
    const std::array<unsigned, 3> widths{paddedWidth, s.chromaWidth, s.chromaWidth};
    const std::array<unsigned, 3> heights{paddedHeight, s.chromaHeight, s.chromaHeight};
    count_ = s.hasChroma ? 3 : 1;
    std::array<uint8_t *, 3> out{}; // the scratch planes this frame converts into; nullptr: used in place
    for (unsigned p = 0; p < count_; ++p) {
        if (mapping.identity() && in[p]->step == 1 && !(p == 0 && lumaPadded)) {
            data_[p] = in[p]->base, strides_[p] = int(in[p]->stride);
            continue;
        }
        scratch_[p].resize(size_t(widths[p]) * heights[p]);
        data_[p] = out[p] = scratch_[p].data(), strides_[p] = int(widths[p]);
    }
    if (s.hasChroma && mapping.mixesChroma())
        convertMatrix(s, mapping, out, lumaOffsets_);
    else
        convertRange(s, mapping, out);
    if (lumaPadded)
        padPlane(out[0], s.width, s.height, paddedWidth, paddedHeight);
    return Ok{};
}

} // namespace overlayd
