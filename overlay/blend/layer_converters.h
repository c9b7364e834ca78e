// SPDX-License-Identifier: Apache-2.0
// Converters from the RGBA overlay layer to a format's native bytes, one per pixel layout, chosen at configure time.
#pragma once

#include "media/pixel_format.h"
#include "overlay/blend/native_runs.h"
#include "overlay/blend/ycbcr.h"
#include "overlay/raster/overlay_layer.h"

namespace overlayd {

using LayerConverter = void (*)(const OverlayLayer &layer, const PixelFormatInfo &format, const YcbcrEncoder &encoder,
                                NativeRuns &out);

LayerConverter layerConverter(PixelLayout layout);

} // namespace overlayd
