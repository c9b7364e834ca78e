// SPDX-License-Identifier: Apache-2.0
// Plain images the converters work on: packed RGB, and planar Y'CbCr with any chroma subsampling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace overlayd {

// 8-bit R, G, B per pixel, rows packed (stride = 3 * width).
struct RgbImage {
    unsigned width = 0, height = 0;
    std::vector<uint8_t> rgb;

    static RgbImage allocate(unsigned width, unsigned height);
    // The same shape in place: the buffer is kept when the size is the same (a per-frame converter faults its
    // pages in once, not every frame). Contents are left for the caller to overwrite.
    void reshape(unsigned width, unsigned height);
    uint8_t *row(unsigned y) { return rgb.data() + size_t(y) * width * 3; }
    const uint8_t *row(unsigned y) const { return rgb.data() + size_t(y) * width * 3; }
};

// Y'CbCr code values in three packed planes; chroma has ceil(width / hSub) x ceil(height / vSub) samples, each
// covering an hSub x vSub macropixel. A luma-only image (GREY, Y4M Cmono) has empty chroma planes.
struct YcbcrImage {
    unsigned width = 0, height = 0;
    unsigned hSub = 1, vSub = 1;
    bool hasChroma = true;
    std::vector<uint8_t> y, cb, cr;

    static YcbcrImage allocate(unsigned width, unsigned height, unsigned hSub, unsigned vSub, bool hasChroma);
    void reshape(unsigned width, unsigned height, unsigned hSub, unsigned vSub, bool hasChroma);
    unsigned chromaWidth() const { return (width + hSub - 1) / hSub; }
    unsigned chromaHeight() const { return (height + vSub - 1) / vSub; }
};

} // namespace overlayd
