// SPDX-License-Identifier: Apache-2.0
// MaskPainter: fills and pixelates masked spans, one sample kind at a time.
#include "overlay/blend/mask_painter.h"

#include <algorithm>
#include <cstring>

#include "overlay/blend/ycbcr.h"

namespace overlayd {

namespace {

enum FillIndex : uint8_t { kY = 0, kCb = 1, kCr = 2, kR = 0, kG = 1, kB = 2, kA = 3 };

} // namespace

MaskPainter::MaskPainter(const PixelFormatInfo &format, Colorimetry colorimetry, unsigned width, unsigned height)
    : colorimetry_(colorimetry), rgb_(format.encoding == ColourEncoding::Rgb), height_(height)
{
    const uint8_t bytes0 = format.planes[0].bytesPerGroup;
    if (rgb_) {
        const std::array<std::pair<uint8_t, uint8_t>, 4> kinds{
            {{format.rOffset, kR}, {format.gOffset, kG}, {format.bOffset, kB}, {format.aOffset, kA}}};
        for (const auto &[offset, index] : kinds)
            if (offset != kNoComponent)
                components_.push_back({0, offset, bytes0, 1, 1, index});
    } else {
        // Luma: a group's second sample sits half a group after its first (yOffset[1] - yOffset[0]).
        components_.push_back({0, format.yOffset[0], uint8_t(bytes0 / format.pixelsPerGroup), 1, 1, kY});
        packed_ = format.layout == PixelLayout::PackedYuv422;
        packedOffsets_ = {format.yOffset[0], format.yOffset[1], format.cbOffset, format.crOffset};
        if (format.cbOffset != kNoComponent) {
            hSub_ = format.hSubSampling, vSub_ = format.vSubSampling;
            components_.push_back({format.cbPlane, format.cbOffset, format.planes[format.cbPlane].bytesPerGroup,
                                   format.hSubSampling, format.vSubSampling, kCb});
            components_.push_back({format.crPlane, format.crOffset, format.planes[format.crPlane].bytesPerGroup,
                                   format.hSubSampling, format.vSubSampling, kCr});
        }
    }
    sums_.assign(width + 1, 0); // a block column per sample at most
    counts_.assign(sums_.size(), 0);
}

unsigned MaskPainter::blockFor(unsigned blockPx) const
{
    const unsigned group = std::max(hSub_, vSub_);
    return std::max(2u, (blockPx + group - 1) / group * group);
}

std::array<uint8_t, 4> MaskPainter::samplesOf(Rgba colour) const
{
    if (rgb_)
        return {colour.r, colour.g, colour.b, 255};
    PremultipliedSum sum;
    const uint8_t opaque[4] = {colour.r, colour.g, colour.b, 255};
    sum.add(opaque);
    const YcbcrBlendSamples s = YcbcrEncoder(colorimetry_).encode(sum);
    return {s.y.value, s.cb.value, s.cr.value, 0};
}

template<typename F>
void MaskPainter::forEachRun(const Component &c, const SpanRows &mask, unsigned row0, unsigned row1, F &&f) const
{
    for (unsigned row = row0; row < row1; ++row)
        for (const RowSpan &s : mask.row(row * c.vSub)) // spans are whole macropixels: its first luma row says
            f(row, unsigned(s.x0) / c.hSub, (unsigned(s.x1) + c.hSub - 1) / c.hSub);
}

void MaskPainter::fill(const FrameView &frame, const SpanRows &mask, Rgba colour) const
{
    const std::array<uint8_t, 4> values = samplesOf(colour);
    if (packed_)
        return fillPacked(frame, mask, values);
    for (const Component &c : components_) {
        const uint8_t value = values[c.fillIndex];
        const unsigned rows = (height_ + c.vSub - 1) / c.vSub;
        forEachRun(c, mask, 0, rows, [&](unsigned row, unsigned first, unsigned end) {
            uint8_t *p = rowStart(frame, c, row) + size_t(first) * c.step;
            if (c.step == 1) { // planar and grey luma, planar chroma
                std::memset(p, value, end - first);
                return;
            }
            for (uint8_t *last = p + size_t(end - first) * c.step; p < last; p += c.step)
                *p = value;
        });
    }
}

void MaskPainter::fillPacked(const FrameView &frame, const SpanRows &mask, const std::array<uint8_t, 4> &values) const
{
    uint8_t pattern[4];
    pattern[packedOffsets_[0]] = pattern[packedOffsets_[1]] = values[kY];
    pattern[packedOffsets_[2]] = values[kCb], pattern[packedOffsets_[3]] = values[kCr];
    for (unsigned y = 0; y < height_; ++y) {
        uint8_t *row = frame.planes[0].data + size_t(y) * frame.planes[0].stride;
        // Spans start on a group; a span ending on an odd width's last pixel takes its whole group, within the row.
        for (const RowSpan &s : mask.row(y))
            for (uint8_t *p = row + size_t(s.x0) * 2, *end = row + size_t(s.x1 + 1) / 2 * 4; p < end; p += 4)
                std::memcpy(p, pattern, 4);
    }
}

void MaskPainter::pixelate(const FrameView &frame, const SpanRows &mask, unsigned blockPx)
{
    const unsigned block = blockFor(blockPx);
    for (const Component &c : components_) {
        const unsigned rows = (height_ + c.vSub - 1) / c.vSub;
        const unsigned bw = block / c.hSub, bh = block / c.vSub; // the block in this component's samples
        // Each run cut at block columns: f(block column, first sample's byte, count).
        const auto eachPiece = [&](unsigned row, unsigned first, unsigned end, auto &&f) {
            uint8_t *p = rowStart(frame, c, row) + size_t(first) * c.step;
            for (unsigned i = first; i < end;) {
                const unsigned stop = std::min(end, (i / bw + 1) * bw);
                f(i / bw, p, stop - i);
                p += size_t(stop - i) * c.step, i = stop;
            }
        };
        for (unsigned band = 0; band < rows; band += bh) {
            const unsigned bandEnd = std::min(rows, band + bh);
            // The average of the masked samples of each block, then written over them: a block comes out uniform
            // and holds nothing of the samples outside the mask.
            forEachRun(c, mask, band, bandEnd, [&](unsigned row, unsigned first, unsigned end) {
                eachPiece(row, first, end, [&](unsigned b, const uint8_t *p, unsigned count) {
                    unsigned sum = 0;
                    for (unsigned k = 0; k < count; ++k, p += c.step)
                        sum += *p;
                    sums_[b] += sum, counts_[b] += count;
                });
            });
            forEachRun(c, mask, band, bandEnd, [&](unsigned row, unsigned first, unsigned end) {
                eachPiece(row, first, end, [&](unsigned b, uint8_t *p, unsigned count) {
                    const uint8_t mean = uint8_t((sums_[b] + counts_[b] / 2) / counts_[b]);
                    for (unsigned k = 0; k < count; ++k, p += c.step)
                        *p = mean;
                });
            });
            forEachRun(c, mask, band, bandEnd, [&](unsigned, unsigned first, unsigned end) {
                for (unsigned b = first / bw; b <= (end - 1) / bw; ++b)
                    sums_[b] = counts_[b] = 0;
            });
        }
    }
}

} // namespace overlayd
