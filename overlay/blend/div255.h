// SPDX-License-Identifier: Apache-2.0
// The one rounding every overlay blend uses, so that the cached layer, the native blend and the direct path agree.
#pragma once

namespace overlayd {

// x / 255 rounded to nearest, exact for x <= 255 * 255, without a division. T is uint16_t in loops the compiler
// should vectorize (16-bit lanes), any wider unsigned type elsewhere.
template<typename T>
constexpr T div255(T x)
{
    x = T(x + 128);
    return T((x + (x >> 8)) >> 8);
}

} // namespace overlayd
