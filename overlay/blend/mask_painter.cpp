// SPDX-License-Identifier: Apache-2.0
// MaskPainter: fills masked spans a sample kind at a time (a packed group or an RGB pixel whole), pixelates them a
// plane and a band of block rows at a time.
#include "overlay/blend/mask_painter.h"

#include <algorithm>
#include <cstring>

#include "overlay/blend/ycbcr.h"
#include "overlay/shapes/annotation.h"

namespace overlayd {

namespace {

enum FillIndex : uint8_t { kY = 0, kCb = 1, kCr = 2, kR = 0, kG = 1, kB = 2, kA = 3 };

constexpr size_t kLine = 64;          // bytes per cache line
constexpr unsigned kPrefetchRows = 4; // how far ahead pixelation asks for rows

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
    // Every byte lane of every plane, classed by the component it holds; a lane that holds none (X) is a class of
    // its own, so a whole group can be written at once.
    pixelsPerGroup_ = format.pixelsPerGroup;
    const unsigned groups = (width + pixelsPerGroup_ - 1) / pixelsPerGroup_;
    size_t widest = 0;
    for (uint8_t p = 0; p < format.numPlanes; ++p) {
        PlanePlan plan{
            .plane = p, .bytesPerGroup = format.planes[p].bytesPerGroup, .vSub = format.planes[p].verticalSubSampling};
        std::array<uint8_t, 4> kind{kNoComponent, kNoComponent, kNoComponent, kNoComponent};
        const auto name = [&](uint8_t plane, uint8_t offset, uint8_t k) {
            if (plane == p && offset < plan.bytesPerGroup)
                kind[offset] = k;
        };
        if (rgb_) {
            name(0, format.rOffset, 0), name(0, format.gOffset, 1), name(0, format.bOffset, 2);
            name(0, format.aOffset, 3);
        } else {
            name(0, format.yOffset[0], 0), name(0, format.yOffset[1], 0);
            name(format.cbPlane, format.cbOffset, 1), name(format.crPlane, format.crOffset, 2);
        }
        for (uint8_t lane = 0; lane < plan.bytesPerGroup; ++lane) {
            uint8_t c = 0;
            while (c < lane && (kind[lane] == kNoComponent || kind[c] != kind[lane]))
                ++c;
            plan.laneClass[lane] = c < lane ? plan.laneClass[c] : plan.classes++;
            ++plan.classLanes[plan.laneClass[lane]];
        }
        if (p == 0 && !rgb_ && width % pixelsPerGroup_ != 0)
            plan.outsideLane = format.yOffset[1];
        plan.groups = groups;
        plan.rows = format.planeHeight(p, height);
        widest = std::max(widest, size_t(groups) * plan.bytesPerGroup);
        planes_.push_back(plan);
    }
    columnSums_.assign(widest, 0);
    means_.assign(widest, 0);
    spanEdges_.assign(groups + 1, 0);
}

unsigned MaskPainter::blockFor(unsigned blockPx) const
{
    // At most 256 rows (kMaxMaskBlockPx, a multiple of every group) of 255 keep a column's sum in 16 bits; the config
    // refuses more.
    static_assert(kMaxMaskBlockPx * 255 <= UINT16_MAX);
    const unsigned group = std::max(hSub_, vSub_);
    return std::max(2u, (std::min(blockPx, kMaxMaskBlockPx) + group - 1) / group * group);
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

void MaskPainter::fill(const FrameView &frame, const SpanRows &mask, Rgba colour)
{
    const std::array<uint8_t, 4> values = samplesOf(colour);
    if (packed_)
        return fillPacked(frame, mask, values);
    if (rgb_)
        return fillRgb(frame, mask, values);
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

void MaskPainter::fillRgb(const FrameView &frame, const SpanRows &mask, const std::array<uint8_t, 4> &values)
{
    // A row of the colour's pixels, copied over each span: whole pixels in wide stores, where a store per sample
    // and component cost 1.3-1.6x the opaque overlay. An X byte takes 255, as an alpha byte does.
    const unsigned bytes = planes_[0].bytesPerGroup;
    uint8_t pixel[4] = {255, 255, 255, 255};
    for (const Component &c : components_)
        pixel[c.offset] = values[c.fillIndex];
    for (size_t k = 0; k < means_.size(); k += bytes)
        std::memcpy(means_.data() + k, pixel, bytes);
    for (unsigned y = 0; y < height_; ++y) {
        uint8_t *row = frame.planes[0].data + size_t(y) * frame.planes[0].stride;
        for (const RowSpan &s : mask.row(y))
            std::memcpy(row + size_t(s.x0) * bytes, means_.data() + size_t(s.x0) * bytes, size_t(s.x1 - s.x0) * bytes);
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
    for (const PlanePlan &plan : planes_) {
        switch (plan.bytesPerGroup) { // the group's size known at compile time: the lane loops unroll
        case 1:
            pixelatePlane<1>(frame, mask, plan, block);
            break;
        case 2:
            pixelatePlane<2>(frame, mask, plan, block);
            break;
        case 3:
            pixelatePlane<3>(frame, mask, plan, block);
            break;
        default:
            pixelatePlane<4>(frame, mask, plan, block);
            break;
        }
    }
}

// A band of block rows at a time, in two passes over its masked bytes: each row's bytes added to a row of column
// sums (a widening add the compiler vectorizes), then the block means, one row of them, copied over each span. In
// between, once per band and not once per row, each block's columns are folded into its classes' sums, and its
// masked groups counted from the spans' ends (+1 where a span starts, -1 where it ends, summed along the row).
template<unsigned Bpg>
void MaskPainter::pixelatePlane(const FrameView &frame, const SpanRows &mask, const PlanePlan &plan, unsigned block)
{
    const PlaneView &view = frame.planes[plan.plane];
    const unsigned blockGroups = block / pixelsPerGroup_, blockRows = block / plan.vSub;
    uint16_t *const sums = columnSums_.data();
    uint8_t *const means = means_.data();
    int32_t *const edges = spanEdges_.data();
    for (unsigned band = 0; band < plan.rows; band += blockRows) {
        const unsigned bandEnd = std::min(plan.rows, band + blockRows);
        unsigned first = plan.groups, end = 0, outsideRows = 0; // the band's masked groups, rows reaching the last
        for (unsigned row = band; row < bandEnd; ++row) {
            const uint8_t *in = view.data + size_t(row) * view.stride;
            // The same columns kPrefetchRows further down are asked for a cache line at a time: the rows are short
            // streams, and the hardware's prefetcher only catches up with each one after a few misses.
            const bool ahead = row + kPrefetchRows < plan.rows;
            for (const RowSpan &s : mask.row(row * plan.vSub)) {
                const unsigned g0 = unsigned(s.x0) / pixelsPerGroup_;
                const unsigned g1 = (unsigned(s.x1) + pixelsPerGroup_ - 1) / pixelsPerGroup_;
                const uint8_t *__restrict src = in + size_t(g0) * Bpg;
                uint16_t *__restrict dst = sums + size_t(g0) * Bpg;
                const size_t n = size_t(g1 - g0) * Bpg;
                for (size_t k = 0; k < n; k += kLine) {
                    if (ahead)
                        __builtin_prefetch(src + k + size_t(kPrefetchRows) * view.stride);
                    for (size_t j = k, stop = std::min(n, k + kLine); j < stop; ++j)
                        dst[j] = uint16_t(dst[j] + src[j]);
                }
                ++edges[g0], --edges[g1];
                first = std::min(first, g0), end = std::max(end, g1);
                outsideRows += g1 == plan.groups;
            }
        }
        if (first >= end)
            continue;
        // Each block's mean per class, spread over its masked bytes: the row of means the spans copy from.
        int32_t rows = 0;                                            // masked rows of the current group column
        unsigned boundary = (first / blockGroups + 1) * blockGroups; // where the current block ends
        for (unsigned g = first; g < end; boundary += blockGroups) {
            const unsigned stop = std::min(end, boundary);
            uint32_t laneSums[Bpg] = {}, groups = 0;
            for (unsigned k = g; k < stop; ++k) {
                rows += edges[k];
                groups += uint32_t(rows);
                for (unsigned lane = 0; lane < Bpg; ++lane)
                    laneSums[lane] += sums[size_t(k) * Bpg + lane];
            }
            if (groups != 0) {
                uint32_t classSums[4] = {}, classCounts[4] = {};
                for (unsigned lane = 0; lane < Bpg; ++lane)
                    classSums[plan.laneClass[lane]] += laneSums[lane], classCounts[plan.laneClass[lane]] += groups;
                if (plan.outsideLane != kNoComponent && stop == plan.groups) {
                    // The last group's lane beyond the frame: taken out of its class's sum and count.
                    classSums[plan.laneClass[plan.outsideLane]] -= sums[size_t(stop - 1) * Bpg + plan.outsideLane];
                    classCounts[plan.laneClass[plan.outsideLane]] -= outsideRows;
                }
                uint8_t classMeans[4] = {}, pattern[Bpg]; // a division per component, not per lane
                for (unsigned c = 0; c < plan.classes; ++c)
                    classMeans[c] = uint8_t((classSums[c] + classCounts[c] / 2) / classCounts[c]);
                for (unsigned lane = 0; lane < Bpg; ++lane)
                    pattern[lane] = classMeans[plan.laneClass[lane]];
                for (unsigned k = g; k < stop; ++k)
                    std::memcpy(means + size_t(k) * Bpg, pattern, Bpg);
            }
            g = stop;
        }
        std::fill(sums + size_t(first) * Bpg, sums + size_t(end) * Bpg, uint16_t(0));
        std::fill(edges + first, edges + end + 1, 0);
        for (unsigned row = band; row < bandEnd; ++row) {
            uint8_t *out = view.data + size_t(row) * view.stride;
            for (const RowSpan &s : mask.row(row * plan.vSub)) {
                const size_t b0 = size_t(unsigned(s.x0) / pixelsPerGroup_) * Bpg;
                const size_t b1 = size_t((unsigned(s.x1) + pixelsPerGroup_ - 1) / pixelsPerGroup_) * Bpg;
                std::memcpy(out + b0, means + b0, b1 - b0);
            }
        }
    }
}

} // namespace overlayd
