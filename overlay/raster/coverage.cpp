// SPDX-License-Identifier: Apache-2.0
// The "over" of a coverage mask in one colour, in 8-bit premultiplied arithmetic.
#include "overlay/raster/coverage.h"

#include "overlay/blend/div255.h"

#include <algorithm>
#include <cstring>

namespace overlayd {

LayerRect LayerRect::intersect(const LayerRect &other) const
{
    return {std::max(x0, other.x0), std::max(y0, other.y0), std::min(x1, other.x1), std::min(y1, other.y1)};
}

void compositeCoverage(const uint8_t *coverage, size_t coverageStride, const LayerRect &rect, Rgba colour,
                       OverlayLayer &layer)
{
    if (rect.empty())
        return;
    const int width = rect.x1 - rect.x0;
    for (int y = rect.y0; y < rect.y1; ++y) {
        const uint8_t *mask = coverage + size_t(y - rect.y0) * coverageStride;
        uint8_t *row = layer.data() + size_t(y) * layer.stride() + size_t(rect.x0) * 4;
        for (int x = 0; x < width; ++x) {
            // A stroke's bounding box is mostly empty: skip eight empty mask bytes at a time.
            for (uint64_t eight = 0; x + 8 <= width; x += 8) {
                std::memcpy(&eight, mask + x, 8);
                if (eight != 0)
                    break;
            }
            if (x >= width || mask[x] == 0)
                continue;
            uint8_t *px = row + size_t(x) * 4;
            if (mask[x] == 255 && colour.a == 255) { // the inside of an opaque stroke: no need to read the layer
                const uint8_t opaque[4] = {colour.r, colour.g, colour.b, 255};
                std::memcpy(px, opaque, 4);
                continue;
            }
            const uint32_t a = div255(uint32_t(mask[x]) * colour.a), keep = 255 - a;
            px[0] = uint8_t(div255(colour.r * a) + div255(px[0] * keep));
            px[1] = uint8_t(div255(colour.g * a) + div255(px[1] * keep));
            px[2] = uint8_t(div255(colour.b * a) + div255(px[2] * keep));
            px[3] = uint8_t(a + div255(px[3] * keep));
        }
    }
}

} // namespace overlayd
