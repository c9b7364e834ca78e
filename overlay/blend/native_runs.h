// SPDX-License-Identifier: Apache-2.0
// NativeRuns: a layer in a frame format's own bytes, as the per-layout converters write it and NativeLayer blends
// it. Each run is the touched bytes of one plane row, with their premultiplied values and inverse alphas. It is a
// class of its own so that the converters write into it without knowing the NativeLayer that calls them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "media/pixel_format.h"
#include "overlay/blend/blend_kernel.h"
#include "overlay/blend/ycbcr.h"

namespace overlayd {

// Where a layer smaller than the frame sits: its pixel (0, 0) on frame pixel (x, y). x and y must be multiples of
// the format's chroma subsampling, and the layer must end on a whole macropixel or at the frame's edge, so that a
// chroma sample never mixes layer pixels with frame pixels the layer does not describe.
struct LayerPlacement {
    unsigned x = 0, y = 0;
    unsigned frameWidth = 0, frameHeight = 0;
};

class NativeRuns
{
public:
    NativeRuns(const PixelFormatInfo &format, const LayerPlacement &placement) : format_(&format), placement_(placement)
    {}

    // Empties the runs, keeping their memory, with room for about `bytes` touched bytes in `runs` runs: the
    // dynamic path re-converts every frame, and fresh vectors would page-fault their way through megabytes.
    void clear(size_t bytes, size_t runs);
    // A run in layer coordinates (converters count in layer pixels); it lands on the frame moved by the placement.
    void beginRun(unsigned plane, unsigned row, unsigned byteOffset);
    void push(BlendSample sample)
    {
        values_.push_back(sample.value);
        inverseAlpha_.push_back(uint8_t(255 - sample.alpha));
    }
    void endRun() { runs_.back().length = uint32_t(values_.size() - runs_.back().dataOffset); }
    // The last run is written: pads the arrays for the blend's read-ahead (kBlendReadAhead).
    void finish();

    const PixelFormatInfo &format() const { return *format_; }
    const LayerPlacement &placement() const { return placement_; }
    const std::vector<NativeRun> &runs() const { return runs_; }
    const uint8_t *values() const { return values_.data(); }
    const uint8_t *inverseAlpha() const { return inverseAlpha_.data(); }
    size_t touchedBytes() const { return values_.size() - kBlendReadAhead; }

private:
    const PixelFormatInfo *format_;
    LayerPlacement placement_;
    std::vector<NativeRun> runs_;
    std::vector<uint8_t> values_;       // premultiplied value per touched byte
    std::vector<uint8_t> inverseAlpha_; // 255 - alpha per touched byte
};

} // namespace overlayd
