// SPDX-License-Identifier: Apache-2.0
// Image files to pixels and back: PNG through libpng, JPEG through libjpeg-turbo, for the image annotations
// (config/), the image-sequence replay and the snapshot sink (drivers/files/). It lives in media/ because both users
// sit above it and media/ already owns libjpeg-turbo; the libraries' headers stay inside codec/'s .cpp files.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "media/codec/image_file.h"
#include "media/convert/images.h"

namespace overlayd {

// Malformed when the bytes are neither a PNG nor a JPEG, or their header does not parse.
Result<ImageFileInfo> readImageInfo(std::span<const uint8_t> file);

// Decodes a whole PNG or JPEG file held in memory. Every PNG colour type and bit depth: grey of 1, 2 or 4 bits and
// palettes are expanded, grey becomes R = G = B, a tRNS chunk becomes alpha, 16 bits become 8 as round(v / 257)
// (what OpenCV's convertTo(CV_8U, 1.0 / 257) gives). Rgb drops alpha without compositing (as OpenCV's IMREAD_COLOR);
// Rgba gives opaque pixels alpha 255. JPEG: greyscale, YCbCr and RGB files as libjpeg-turbo decodes them (accurate
// DCT, smooth upsampling); the EXIF orientation is not applied. An image wider or taller than maxSide is refused
// (Unsupported) from its header, before anything is allocated; a truncated or corrupt file is Malformed with the
// library's reason (a JPEG that libjpeg-turbo would patch up with a warning is refused too); a CMYK JPEG is
// Unsupported.
Result<DecodedImage> decodeImage(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide);

// An 8-bit RGB PNG, compressed for speed (the SUB filter, zlib level 1, run-length strategy: OpenCV's imencode
// defaults).
Result<std::vector<uint8_t>> encodePng(const RgbImage &image);

// A baseline JFIF at quality 1..100 with 4:2:0 chroma and the accurate DCT: the bytes OpenCV's imencode writes.
Result<std::vector<uint8_t>> encodeJpeg(const RgbImage &image, int quality);

} // namespace overlayd
