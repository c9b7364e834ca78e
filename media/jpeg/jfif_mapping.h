// SPDX-License-Identifier: Apache-2.0
// JfifMapping: a frame's Y'CbCr code values, in the frame's own colorimetry, to the full-range BT.601 code values
// that JFIF defines and every JPEG decoder assumes, as 256-entry tables built once per colorimetry.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "media/colorimetry.h"

namespace overlayd {

// Both matrices send a grey (Cb = Cr = 128) to the same grey, so after range expansion the conversion has the shape
//   Y'' = Y' + dY(Cb, Cr),  Cb'' = g(Cb, Cr),  Cr'' = h(Cb, Cr):
// chroma never depends on luma, and luma only gains an offset that depends on its own chroma sample. Chroma is
// therefore converted once per chroma site and each pixel's luma gets its site's offset, which is exact (no luma
// averaging) for the nearest-neighbour chroma that frameToRgb, our reference, reconstructs with.
class JfifMapping
{
public:
    explicit JfifMapping(Colorimetry colorimetry);

    Colorimetry colorimetry() const { return colorimetry_; }
    // Already full-range BT.601: samples can go to the encoder as they are.
    bool identity() const { return colorimetry_ == Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full}; }
    // Another matrix than BT.601: luma depends on chroma, so the per-sample tables below are not enough.
    bool mixesChroma() const { return colorimetry_.matrix != YcbcrMatrix::Bt601; }

    // Range expansion only, 256 entries each (exact for BT.601, and all there is for luma-only frames).
    const uint8_t *lumaTable() const { return lumaBytes_.data(); }
    const uint8_t *chromaTable() const { return chromaBytes_.data(); }

    // The full conversion, in 16.16 fixed point (16 fractional bits keep the sum of three table entries well
    // within half a code value of the exact result).
    int32_t lumaOffset(uint8_t cb, uint8_t cr) const { return cbToY_[cb] + crToY_[cr]; }
    uint8_t luma(uint8_t y, int32_t offset) const { return clampCode(yFixed_[y] + offset); }
    uint8_t cb(uint8_t cb, uint8_t cr) const { return clampCode(cbToCb_[cb] + crToCb_[cr]); }
    uint8_t cr(uint8_t cb, uint8_t cr) const { return clampCode(cbToCr_[cb] + crToCr_[cr]); }

private:
    using Bytes = std::array<uint8_t, 256>;
    using Fixed = std::array<int32_t, 256>;

    // The rounding bias is already in the tables that carry a base value (yFixed_, cbToCb_, crToCr_).
    static uint8_t clampCode(int32_t fixed) { return uint8_t(std::clamp(fixed >> 16, 0, 255)); }

    Colorimetry colorimetry_;
    Bytes lumaBytes_{}, chromaBytes_{};
    Fixed yFixed_{}, cbToY_{}, crToY_{}, cbToCb_{}, crToCb_{}, cbToCr_{}, crToCr_{};
};

} // namespace overlayd
