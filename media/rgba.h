// SPDX-License-Identifier: Apache-2.0
// Rgba: a straight (not premultiplied) sRGB colour with alpha, as a user writes it in the config.
#pragma once

#include <cstdint>

namespace overlayd {

struct Rgba {
    uint8_t r = 0, g = 0, b = 0, a = 255;

    friend bool operator==(const Rgba &, const Rgba &) = default;
};

} // namespace overlayd
