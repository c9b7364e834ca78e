// SPDX-License-Identifier: Apache-2.0
// NativeLayer: conversion at configure time, and the per-frame blend over its runs.
#include "overlay/blend/native_layer.h"

#include <string>

#include "overlay/blend/blend_kernel.h"
#include "overlay/blend/layer_converters.h"

namespace overlayd {

namespace {

Status checkPlacement(const OverlayLayer &layer, const PixelFormatInfo &format, const LayerPlacement &p)
{
    const bool fits = p.x + layer.width() <= p.frameWidth && p.y + layer.height() <= p.frameHeight;
    const bool aligned = p.x % format.hSubSampling == 0 && p.y % format.vSubSampling == 0;
    const bool wholeRight = layer.width() % format.hSubSampling == 0 || p.x + layer.width() == p.frameWidth;
    const bool wholeBottom = layer.height() % format.vSubSampling == 0 || p.y + layer.height() == p.frameHeight;
    if (fits && aligned && wholeRight && wholeBottom)
        return Ok{};
    return makeError(ErrorCode::InvalidArgument,
                     "a " + std::to_string(layer.width()) + "x" + std::to_string(layer.height()) + " layer at " +
                         std::to_string(p.x) + "," + std::to_string(p.y) + " does not fit " + std::string(format.name) +
                         " macropixels of a " + std::to_string(p.frameWidth) + "x" + std::to_string(p.frameHeight) +
                         " frame");
}

} // namespace

Result<NativeLayer> NativeLayer::convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                         Colorimetry colorimetry)
{
    return convert(layer, format, colorimetry, {0, 0, layer.width(), layer.height()});
}

Result<NativeLayer> NativeLayer::convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                         Colorimetry colorimetry, const LayerPlacement &placement)
{
    if (layer.width() == 0 || layer.height() == 0)
        return makeError(ErrorCode::InvalidArgument, "overlay layer is empty");
    if (Status status = checkPlacement(layer, format, placement); !status)
        return status.error();
    NativeLayer out(format, placement);
    if (Status status = out.update(layer, colorimetry); !status)
        return status.error();
    return out;
}

Status NativeLayer::update(const OverlayLayer &layer, Colorimetry colorimetry)
{
    const LayerPlacement &placement = runs_.placement();
    if (layer.width() + placement.x > placement.frameWidth || layer.height() + placement.y > placement.frameHeight)
        return makeError(ErrorCode::InvalidArgument, "layer does not fit the frame it was converted for");
    const PixelFormatInfo &format = runs_.format();
    // Covered pixels times bytes per pixel, plus whole macropixels at span ends: enough for one allocation.
    runs_.clear(layer.coveredPixels() * (format.bitsPerPixel + 7) / 8 * 3 / 2 + 64, layer.spans().size() * 2);
    layerConverter(format.layout)(layer, format, YcbcrEncoder(colorimetry), runs_);
    runs_.finish();
    return Ok{};
}

Status NativeLayer::blend(const FrameView &frame) const
{
    const PixelFormatInfo &format = runs_.format();
    const unsigned width = runs_.placement().frameWidth, height = runs_.placement().frameHeight;
    if (!frame.format || frame.format->fourcc != format.fourcc || frame.width != width || frame.height != height)
        return makeError(ErrorCode::InvalidArgument, "frame does not match the overlay's " + std::string(format.name) +
                                                         " " + std::to_string(width) + "x" + std::to_string(height));
    if (Status status = checkFrame(frame); !status)
        return status;
    blendChecked(frame);
    return Ok{};
}

void NativeLayer::blendChecked(const FrameView &frame) const
{
    blendRuns(frame, runs_.runs(), runs_.values(), runs_.inverseAlpha());
}

} // namespace overlayd
