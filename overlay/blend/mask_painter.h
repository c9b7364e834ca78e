// SPDX-License-Identifier: Apache-2.0
// MaskPainter: a privacy mask burned into a frame in its own pixel format -- the masked pixels take one colour, or
// the average of their block, sample plane by sample plane (luma and chroma averaged apart, no round trip through
// RGB). The spans come widened to whole macropixels (SpanRows with the format's subsampling), so every chroma
// sample a masked pixel uses is masked with it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/rgba.h"
#include "overlay/raster/polygon_spans.h"

namespace overlayd {

class MaskPainter
{
public:
    MaskPainter(const PixelFormatInfo &format, Colorimetry colorimetry, unsigned width, unsigned height);

    // The horizontal and vertical subsampling masks are widened to (SpanRows' hSub and vSub).
    unsigned hSub() const { return hSub_; }
    unsigned vSub() const { return vSub_; }
    // The block a pixelation uses for block_px: rounded up to whole macropixels (at most kMaxMaskBlockPx).
    unsigned blockFor(unsigned blockPx) const;

    // The frame was checked against the format and size (the renderer's blend does); no allocation.
    void fill(const FrameView &frame, const SpanRows &mask, Rgba colour);
    void pixelate(const FrameView &frame, const SpanRows &mask, unsigned blockPx);

private:
    // One kind of sample (Y, Cb, Cr, R, G, B, A): sample i of a row is byte offset + i * step of its plane (every
    // format of the table keeps a kind of sample evenly spaced: YUYV's luma 2 bytes apart, its chroma 4); one sample
    // covers hSub x vSub pixels.
    struct Component {
        uint8_t plane = 0, offset = 0, step = 1;
        uint8_t hSub = 1, vSub = 1;
        uint8_t fillIndex = 0; // which of the fill's samples it takes (see samplesOf)
    };

    void fillPacked(const FrameView &frame, const SpanRows &mask, const std::array<uint8_t, 4> &values) const;
    void fillRgb(const FrameView &frame, const SpanRows &mask, const std::array<uint8_t, 4> &values);
    // The fill colour's code value per fillIndex.
    std::array<uint8_t, 4> samplesOf(Rgba colour) const;
    uint8_t *rowStart(const FrameView &frame, const Component &c, unsigned row) const
    {
        return frame.planes[c.plane].data + size_t(row) * frame.planes[c.plane].stride + c.offset;
    }
    // Calls f(row, first, end) for every run of masked samples of the component's rows [row0, row1).
    template<typename F>
    void forEachRun(const Component &c, const SpanRows &mask, unsigned row0, unsigned row1, F &&f) const;

    // A plane as pixelate sees it: groups of bytesPerGroup bytes covering pixelsPerGroup pixels of vSub rows, each
    // byte lane averaged with the other lanes of its class (a packed 4:2:2 group's two Y, or a lane alone).
    struct PlanePlan {
        uint8_t plane = 0, bytesPerGroup = 1, vSub = 1;
        uint8_t laneClass[4]{};
        uint8_t classLanes[4]{}; // lanes per class
        uint8_t classes = 0;
        // A frame of odd width leaves its last group's second luma pixel outside the frame: that lane is neither
        // counted nor averaged (kNoComponent when every lane is a pixel of the frame).
        uint8_t outsideLane = kNoComponent;
        unsigned groups = 0, rows = 0; // per row; rows of the plane
    };
    template<unsigned BytesPerGroup>
    void pixelatePlane(const FrameView &frame, const SpanRows &mask, const PlanePlan &plan, unsigned block);

    std::vector<Component> components_;
    std::vector<PlanePlan> planes_;
    Colorimetry colorimetry_;
    bool rgb_ = false;
    // Packed 4:2:2 (YUYV and kin): a fill writes whole macropixels, one 4-byte pattern each, in one pass.
    std::array<uint8_t, 4> packedOffsets_{}; // Y0, Y1, Cb, Cr within a group
    bool packed_ = false;
    unsigned height_;
    unsigned hSub_ = 1, vSub_ = 1, pixelsPerGroup_ = 1;
    // Scratch sized once: a band's column sums (one per byte of a plane row), the row of block means written back
    // (or of an RGB fill's pixels), spans starting minus spans ending at each group column.
    std::vector<uint16_t> columnSums_;
    std::vector<uint8_t> means_;
    std::vector<int32_t> spanEdges_;
};

} // namespace overlayd
