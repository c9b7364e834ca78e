// SPDX-License-Identifier: Apache-2.0
// NativeLayer: an OverlayLayer converted once into a frame format's own bytes, blended into every frame.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/pixel_format.h"
#include "overlay/blend/native_runs.h"
#include "overlay/raster/overlay_layer.h"

namespace overlayd {

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

    const PixelFormatInfo &format() const { return runs_.format(); }
    const std::vector<NativeRun> &runs() const { return runs_.runs(); }
    size_t touchedBytes() const { return runs_.touchedBytes(); }

private:
    NativeLayer(const PixelFormatInfo &format, const LayerPlacement &placement) : runs_(format, placement) {}

    NativeRuns runs_;
};

} // namespace overlayd
