// SPDX-License-Identifier: Apache-2.0
// The two file formats behind image_codec.h, one file each (png_file.cpp, jpeg_file.cpp); image_codec.cpp picks one
// by the file's signature.
#pragma once

#include <cstdint>
#include <span>

#include "base/result.h"
#include "media/codec/image_file.h"

namespace overlayd {

bool isPng(std::span<const uint8_t> file);
bool isJpeg(std::span<const uint8_t> file);

Result<ImageFileInfo> pngInfo(std::span<const uint8_t> file);
// The header is checked against maxSide before the pixels are allocated.
Result<DecodedImage> decodePng(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide);

Result<ImageFileInfo> jpegInfo(std::span<const uint8_t> file);
Result<DecodedImage> decodeJpeg(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide);

// Unsupported, naming both sides, when the header says the image is larger than maxSide.
Status checkSide(const ImageFileInfo &info, unsigned maxSide);

} // namespace overlayd
