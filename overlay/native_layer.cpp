// NativeLayer: conversion at configure time, and the per-frame blend over its runs.
#include "overlay/native_layer.h"

#include <string>

#include "overlay/blend_kernel.h"
#include "overlay/layer_converters.h"

namespace overlayd {

Result<NativeLayer> NativeLayer::convert(const OverlayLayer &layer, const PixelFormatInfo &format,
                                         Colorimetry colorimetry)
{
    if (layer.width() == 0 || layer.height() == 0)
        return makeError(ErrorCode::InvalidArgument, "overlay layer is empty");
    NativeLayer out(format, layer.width(), layer.height());
    layerConverter(format.layout)(layer, format, YcbcrEncoder(colorimetry), out);
    return out;
}

void NativeLayer::beginRun(unsigned plane, unsigned row, unsigned byteOffset)
{
    runs_.push_back({plane, row, byteOffset, 0, uint32_t(values_.size())});
}

Status NativeLayer::blend(const FrameView &frame) const
{
    if (!frame.format || frame.format->fourcc != format_->fourcc || frame.width != width_ || frame.height != height_)
        return makeError(ErrorCode::InvalidArgument, "frame does not match the overlay's " +
                                                         std::string(format_->name) + " " + std::to_string(width_) +
                                                         "x" + std::to_string(height_));
    if (Status status = checkFrame(frame); !status)
        return status;
    blendRuns(frame, runs_, values_.data(), inverseAlpha_.data());
    return Ok{};
}

} // namespace overlayd
