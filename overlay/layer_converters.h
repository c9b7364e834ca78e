// Converters from the RGBA overlay layer to a format's native bytes, one per pixel layout, chosen at configure time.
#pragma once

#include "drivers/pixel_format.h"
#include "overlay/native_layer.h"
#include "overlay/overlay_layer.h"
#include "overlay/ycbcr.h"

namespace overlayd {

using LayerConverter = void (*)(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                                NativeLayer &out);

LayerConverter layerConverter(PixelLayout layout);

} // namespace overlayd
