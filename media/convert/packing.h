// SPDX-License-Identifier: Apache-2.0
// Moving samples between a frame in any format of the table and the converters' plain images, driven by the
// table entry's plane layout and byte offsets (never by the fourcc).
#pragma once

#include "base/result.h"
#include "media/convert/images.h"
#include "media/frame.h"

namespace overlayd {

// Y'CbCr formats and GREY. The image's subsampling must be the format's (YcbcrImage for a format: see
// ycbcrImageFor); GREY ignores chroma.
Status packYcbcr(const YcbcrImage &image, const FrameView &frame);
Result<YcbcrImage> unpackYcbcr(const FrameView &frame);
// The same into `image`, reshaped (its buffers kept when the size is the same).
Status unpackYcbcr(const FrameView &frame, YcbcrImage &image);
// An empty image shaped for the format's subsampling.
YcbcrImage ycbcrImageFor(const PixelFormatInfo &format, unsigned width, unsigned height);

// Packed RGB formats: alpha is written opaque, padding (X) bytes 0.
Status packRgb(const RgbImage &image, const FrameView &frame);
Result<RgbImage> unpackRgb(const FrameView &frame);
Status unpackRgb(const FrameView &frame, RgbImage &image);

} // namespace overlayd
