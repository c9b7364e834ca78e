// SPDX-License-Identifier: Apache-2.0
// The frame sink's 16-bit lane arithmetic (overlay/blend/sink_lanes.h) against the chroma rule written in plain integer
// and floating-point maths, for every four-pixel opacity sum and every code: the lanes may not overflow anywhere.
#include "overlay/blend/sink_lanes.h"

#include <cfenv>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

constexpr unsigned kMaxSum = 4 * 255; // four pixels' opacity

// The mean opacity s / 4, rounded half to even as lrintf rounds it on the cached path.
unsigned meanOpacity(unsigned sum4)
{
    std::fesetround(FE_TONEAREST);
    return unsigned(std::nearbyint(sum4 / 4.0));
}

// The code at full opacity scaled to that mean: round(s * code / 1020), halves up, capped at the mean opacity.
unsigned scaledCode(unsigned sum4, unsigned code)
{
    const uint64_t value = (uint64_t(sum4) * code * 2 + 1020) / 2040;
    return unsigned(std::min<uint64_t>(value, meanOpacity(sum4)));
}

TEST(SinkLanes, MeanAlphaRoundsHalfToEvenForEverySum)
{
    for (unsigned s = 0; s <= kMaxSum; s += 8) {
        Words8 sums;
        for (unsigned lane = 0; lane < 8; ++lane)
            sums[lane] = uint16_t(std::min(s + lane, kMaxSum));
        const Words8 alpha = meanAlpha8(sums);
        for (unsigned lane = 0; lane < 8; ++lane) {
            ASSERT_EQ(alpha[lane], meanOpacity(sums[lane])) << "sum " << sums[lane];
            ASSERT_EQ(meanAlpha(sums[lane]), meanOpacity(sums[lane])) << "sum " << sums[lane];
        }
    }
}

TEST(SinkLanes, ScaledBySumMatchesTheRuleForEverySumAndCode)
{
    for (unsigned code = 0; code <= 255; ++code) {
        for (unsigned s = 0; s <= kMaxSum; s += 8) {
            Words8 sums, codes = Words8{} + uint16_t(code);
            for (unsigned lane = 0; lane < 8; ++lane)
                sums[lane] = uint16_t(std::min(s + lane, kMaxSum));
            const Words8 value = scaledBySum(sums, codes, meanAlpha8(sums));
            for (unsigned lane = 0; lane < 8; ++lane) {
                ASSERT_EQ(value[lane], scaledCode(sums[lane], code)) << "sum " << sums[lane] << " code " << code;
                ASSERT_EQ(scaled(sums[lane], code, meanAlpha(sums[lane])), scaledCode(sums[lane], code));
            }
        }
    }
}

} // namespace
} // namespace overlayd
