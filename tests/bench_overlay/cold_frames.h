// Cold frames for the overlay benchmarks: a ring of frames larger than the caches, and the baseline every ratio is
// measured against, a cold memcpy of one frame.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include <benchmark/benchmark.h>

#include "drivers/frame.h"
#include "drivers/pixel_format.h"

namespace overlayd::bench {

inline constexpr size_t kRingBytes = size_t(96) << 20;

struct Ring {
    FrameLayout layout;
    std::vector<uint8_t> bytes;
    size_t count;

    Ring(const PixelFormatInfo &format, unsigned width, unsigned height)
        : layout(*makeFrameLayout(format, width, height)), count(kRingBytes / layout.totalSize + 1)
    {
        bytes.assign(layout.totalSize * count, 0x80);
    }
    uint8_t *frame(size_t i) { return bytes.data() + (i % count) * layout.totalSize; }
};

inline void memcpyBench(benchmark::State &state, const char *formatName, unsigned width, unsigned height)
{
    Ring ring(*pixelFormatFromName(formatName), width, height);
    size_t i = 0;
    for (auto _ : state) {
        std::memcpy(ring.frame(i + ring.count / 2), ring.frame(i), ring.layout.totalSize);
        benchmark::ClobberMemory();
        ++i;
    }
}

} // namespace overlayd::bench
