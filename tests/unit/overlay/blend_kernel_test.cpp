// SPDX-License-Identifier: Apache-2.0
// The blend arithmetic, exhaustively: every frame value under every alpha and premultiplied colour.
#include "overlay/blend/blend_kernel.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace overlayd {
namespace {

TEST(BlendKernel, ExactRoundedOverForAllInputs)
{
    // A whole run of 256 frame values per (alpha, colour), so the vectorized body and its tail both run.
    std::vector<uint8_t> dst(256), values(256), inverse(256);
    int worst = 0;
    for (int a = 0; a <= 255; ++a) {
        for (int c = 0; c <= 255; c += 5) {
            const int premul = (c * a + 127) / 255;
            for (int d = 0; d < 256; ++d)
                dst[d] = d, values[d] = premul, inverse[d] = 255 - a;
            blendBytes(dst.data(), values.data(), inverse.data(), dst.size());
            for (int d = 0; d < 256; ++d) {
                const int expected = premul + int(std::lround(d * (255 - a) / 255.0));
                ASSERT_EQ(dst[d], expected) << "a " << a << " c " << c << " d " << d;
                worst = std::max(worst, std::abs(dst[d] - int(std::lround(c * a / 255.0 + d * (1 - a / 255.0)))));
            }
        }
    }
    // Against the exact real-valued "over", two roundings cost at most one code.
    EXPECT_LE(worst, 1);
}

} // namespace
} // namespace overlayd
