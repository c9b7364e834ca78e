// SPDX-License-Identifier: Apache-2.0
// R'G'B' <-> Y'CbCr for whole images in a named colorimetry, and chroma resampling between subsamplings.
#pragma once

#include "media/colorimetry.h"
#include "media/convert/images.h"

namespace overlayd {

// Chroma of each hSub x vSub macropixel is the mean of its pixels' chroma (only the pixels that exist at an odd
// right or bottom edge). Without chroma, only luma is computed.
YcbcrImage rgbToYcbcr(const RgbImage &image, Colorimetry colorimetry, unsigned hSub, unsigned vSub, bool hasChroma);
// The same into `out`, reshaped (its buffers kept when the size is the same).
void rgbToYcbcr(const RgbImage &image, Colorimetry colorimetry, unsigned hSub, unsigned vSub, bool hasChroma,
                YcbcrImage &out);

// Each pixel takes the chroma sample of its macropixel (nearest, no interpolation); luma-only images give grey.
RgbImage ycbcrToRgb(const YcbcrImage &image, Colorimetry colorimetry);

// The same image with another chroma subsampling: each new sample is the mean, over the pixels of its macropixel,
// of the old sample covering each pixel (so downsampling averages and upsampling repeats).
YcbcrImage resampleChroma(const YcbcrImage &image, unsigned hSub, unsigned vSub);

} // namespace overlayd
