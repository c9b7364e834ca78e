// SPDX-License-Identifier: Apache-2.0
// Whole-frame conversion between RGB or Y'CbCr images and a frame in any format of the pixel-format table, for
// test patterns, image replay, PNG/JPEG snapshots, Y4M and "NO SIGNAL" frames. Not the per-frame hot path: each
// call converts whole rows through one intermediate image.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "media/colorimetry.h"
#include "media/convert/images.h"
#include "media/frame.h"

namespace overlayd {

// RGB formats take the pixels as they are; Y'CbCr formats encode them in `colorimetry` with chroma averaged over
// each macropixel; GREY keeps luma.
Status rgbToFrame(const RgbImage &image, Colorimetry colorimetry, const FrameView &frame);
Result<RgbImage> frameToRgb(const FrameView &frame, Colorimetry colorimetry);

// Y'CbCr samples into any format: resampled to the format's chroma subsampling when it differs, or decoded to RGB
// for RGB formats.
Status ycbcrToFrame(const YcbcrImage &image, Colorimetry colorimetry, const FrameView &frame);
// The frame's samples as planar Y'CbCr: Y'CbCr formats unpack losslessly (their own subsampling), RGB formats are
// encoded at 4:4:4, GREY stays luma-only.
Result<YcbcrImage> frameToYcbcr(const FrameView &frame, Colorimetry colorimetry);
// The same into `out` for a per-frame caller (the Y4M sink): `out` and the RGB scratch keep their buffers from one
// frame to the next, so nothing is allocated or faulted in per frame once the size is steady.
Status frameToYcbcr(const FrameView &frame, Colorimetry colorimetry, YcbcrImage &out, RgbImage &rgbScratch);

// Every pixel one colour (the "NO SIGNAL" background, tests).
Status fillFrame(const FrameView &frame, Colorimetry colorimetry, uint8_t r, uint8_t g, uint8_t b);

} // namespace overlayd
