// SPDX-License-Identifier: Apache-2.0
// NativeLayer: an OverlayLayer converted once into a frame format's own bytes, blended into every frame.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/pixel_format.h"
#include "overlay/blend/blend_kernel.h"
#include "overlay/blend/ycbcr.h"
#include "overlay/raster/overlay_layer.h"

namespace overlayd {

// Where a layer smaller than the frame sits: its pixel (0, 0) on frame pixel (x, y). x and y must be multiples of
// the format's chroma subsampling, and the layer must end on a whole macropixel or at the frame's edge, so that a
// chroma sample never mixes layer pixels with frame pixels the layer does not describe.
struct LayerPlacement {
    unsigned x = 0, y = 0;
    unsigned frameWidth = 0, frameHeight = 0;
};

class NativeLayer
{
public:
    // Configure time: converts the layer for one format and colorimetry (the colorimetry is unused for RGB formats).
    static Result<NativeLayer> convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                       Colorimetry colorimetry);
    // The same for a layer placed on a larger frame (a small text layer).
    static Result<NativeLayer> convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                       Colorimetry colorimetry, const LayerPlacement &placement);

    // Re-converts a redrawn layer of the same size and placement, reusing this layer's memory (the dynamic path:
    // fresh vectors would page-fault their way through megabytes every frame).
    Status update(const OverlayLayer &layer, Colorimetry colorimetry);

    // Frame path: blends into the frame in place; touches only the bytes of the layer's runs. The frame must have
    // the format and size the layer was converted for; its strides may be anything its format allows.
    Status blend(const FrameView &frame) const;
    // The same for a caller that has already checked the frame once for all its layers (the scene renderer).
    void blendChecked(const FrameView &frame) const;

    const PixelFormatInfo &format() const { return *format_; }
    const std::vector<NativeRun> &runs() const { return runs_; }
    size_t touchedBytes() const { return values_.size() - kBlendReadAhead; }

    // Used by the per-layout converters while building the layer.
    void beginRun(unsigned plane, unsigned row, unsigned byteOffset);
    void push(BlendSample sample)
    {
        values_.push_back(sample.value);
        inverseAlpha_.push_back(uint8_t(255 - sample.alpha));
    }
    void endRun() { runs_.back().length = values_.size() - runs_.back().dataOffset; }

private:
    NativeLayer(const PixelFormatInfo &format, const LayerPlacement &placement)
        : format_(&format), width_(placement.frameWidth), height_(placement.frameHeight), placement_(placement)
    {}

    const PixelFormatInfo *format_;
    unsigned width_, height_; // of the frame
    LayerPlacement placement_;
    std::vector<NativeRun> runs_;
    std::vector<uint8_t> values_;       // premultiplied value per touched byte
    std::vector<uint8_t> inverseAlpha_; // 255 - alpha per touched byte
};

} // namespace overlayd
