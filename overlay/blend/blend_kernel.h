// SPDX-License-Identifier: Apache-2.0
// The per-frame blend: one premultiplied "over" per touched byte, the same for every pixel format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "media/frame.h"

namespace overlayd {

// length bytes of row `row` of plane `plane`, starting at byteOffset, take their values from the layer's arrays
// at dataOffset. Runs are in plane-byte units, so the blend never needs to know the format.
struct NativeRun {
    uint32_t plane = 0, row = 0, byteOffset = 0, length = 0;
    uint32_t dataOffset = 0;
};

// dst[i] = values[i] + round(dst[i] * inverseAlpha[i] / 255). Exact for 8-bit inputs; never overflows because
// every value is <= 255 - inverseAlpha.
void blendBytes(uint8_t *__restrict dst, const uint8_t *__restrict values, const uint8_t *__restrict inverseAlpha,
                size_t count);

// blendRuns reads up to this many bytes of values and inverseAlpha past a run's start (short runs are one
// masked vector operation), so the arrays extend this far beyond their last run.
inline constexpr size_t kBlendReadAhead = 16;

// blendBytes over every run; the frame must already be checked against the runs' format and size.
void blendRuns(const FrameView &frame, std::span<const NativeRun> runs, const uint8_t *values,
               const uint8_t *inverseAlpha);

} // namespace overlayd
