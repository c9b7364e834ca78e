// SPDX-License-Identifier: Apache-2.0
// What an image file is and what decoding it gives: the types image_codec.h's functions and the two formats behind
// them (formats.h) share, here so that neither header includes the other.
#pragma once

#include <cstdint>
#include <vector>

namespace overlayd {

enum class ImageFileType { Png, Jpeg };

// What a file's header says, read before any pixel is decoded: enough to refuse an image too large to allocate.
struct ImageFileInfo {
    ImageFileType type = ImageFileType::Png;
    unsigned width = 0, height = 0;
};

enum class ImageChannels { Rgb = 3, Rgba = 4 };

// 8-bit samples, rows packed (stride = channels * width): R G B, or R G B A with straight (not premultiplied) alpha.
struct DecodedImage {
    unsigned width = 0, height = 0;
    ImageChannels channels = ImageChannels::Rgb;
    std::vector<uint8_t> pixels;
};

} // namespace overlayd
