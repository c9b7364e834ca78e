// NativeLayer: an OverlayLayer converted once into a frame format's own bytes, blended into every frame.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/colorimetry.h"
#include "drivers/frame.h"
#include "drivers/pixel_format.h"
#include "overlay/blend_kernel.h"
#include "overlay/overlay_layer.h"
#include "overlay/ycbcr.h"
#include "projection/result.h"

namespace overlayd {

class NativeLayer
{
public:
    // Configure time: converts the layer for one format and colorimetry (the colorimetry is unused for RGB formats).
    static Result<NativeLayer> convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                       Colorimetry colorimetry);

    // Frame path: blends into the frame in place; touches only the bytes of the layer's runs. The frame must have
    // the format and size the layer was converted for; its strides may be anything its format allows.
    Status blend(const FrameView &frame) const;

    const PixelFormatInfo &format() const { return *format_; }
    const std::vector<NativeRun> &runs() const { return runs_; }
    size_t touchedBytes() const { return values_.size(); }

    // Used by the per-layout converters while building the layer.
    void beginRun(unsigned plane, unsigned row, unsigned byteOffset);
    void push(BlendSample sample)
    {
        values_.push_back(sample.value);
        inverseAlpha_.push_back(uint8_t(255 - sample.alpha));
    }
    void endRun() { runs_.back().length = values_.size() - runs_.back().dataOffset; }

private:
    NativeLayer(const PixelFormatInfo &format, unsigned width, unsigned height)
        : format_(&format), width_(width), height_(height)
    {}

    const PixelFormatInfo *format_;
    unsigned width_, height_;
    std::vector<NativeRun> runs_;
    std::vector<uint8_t> values_;       // premultiplied value per touched byte
    std::vector<uint8_t> inverseAlpha_; // 255 - alpha per touched byte
};

} // namespace overlayd
