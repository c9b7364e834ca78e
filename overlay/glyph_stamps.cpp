// SPDX-License-Identifier: Apache-2.0
// GlyphStamps: a stamp is the glyph's coverage composited in the item's colour on a layer of its macropixel-aligned
// box, converted once to the frame's format.
#include "overlay/glyph_stamps.h"

#include <algorithm>

#include "overlay/raster/coverage.h"

namespace overlayd {

LayerRect macropixelAligned(LayerRect box, const PixelFormatInfo &format, unsigned frameWidth, unsigned frameHeight)
{
    const int h = format.hSubSampling, v = format.vSubSampling;
    const int width = int(frameWidth), height = int(frameHeight);
    const int x0 = std::max(box.x0, 0) / h * h, y0 = std::max(box.y0, 0) / v * v;
    const int x1 = std::min((std::min(box.x1, width) + h - 1) / h * h, width);
    const int y1 = std::min((std::min(box.y1, height) + v - 1) / v * v, height);
    return {x0, y0, x1, y1};
}

Status GlyphStamps::blend(const TextRenderer &text, const TextItem &item, glm::ivec2 origin, const LayerRect &clip,
                          const FrameView &frame)
{
    for (const TextRenderer::PlacedGlyph &glyph : text.placeGlyphs(item.text, item.sizePx, item.antialias)) {
        const glm::ivec2 at = origin + glm::ivec2(glyph.x, glyph.y);
        // A place is a frame pixel, give or take a text's size: 21 bits each are unique for |x|, |y| < 2^20.
        const uint64_t key = uint64_t(glyph.codepoint) << 42 | uint64_t(uint32_t(at.x) & 0x1fffff) << 21 |
                             uint64_t(uint32_t(at.y) & 0x1fffff);
        auto found = stamps_.find(key);
        if (found == stamps_.end()) {
            if (stamps_.size() >= kMaxGlyphStamps)
                stamps_.clear();
            auto stamp = make(glyph, at, item.colour, clip);
            if (!stamp)
                return stamp.error();
            found = stamps_.emplace(key, std::move(*stamp)).first;
        }
        if (found->second)
            found->second->blendChecked(frame);
    }
    return Ok{};
}

Result<std::optional<NativeLayer>> GlyphStamps::make(const TextRenderer::PlacedGlyph &glyph, glm::ivec2 at, Rgba colour,
                                                     const LayerRect &clip) const
{
    const LayerRect ink = LayerRect{at.x, at.y, at.x + glyph.width, at.y + glyph.rows}.intersect(clip);
    if (ink.empty())
        return std::optional<NativeLayer>();
    const LayerRect box = macropixelAligned(ink, *format_.format, format_.width, format_.height);
    OverlayLayer pixels(unsigned(box.x1 - box.x0), unsigned(box.y1 - box.y0));
    const uint8_t *coverage = glyph.coverage + size_t(ink.y0 - at.y) * size_t(glyph.width) + size_t(ink.x0 - at.x);
    compositeCoverage(coverage, size_t(glyph.width),
                      {ink.x0 - box.x0, ink.y0 - box.y0, ink.x1 - box.x0, ink.y1 - box.y0}, colour, pixels);
    pixels.updateSpans();
    auto native = NativeLayer::convert(pixels, *format_.format, colorimetry_,
                                       {unsigned(box.x0), unsigned(box.y0), format_.width, format_.height});
    if (!native)
        return native.error();
    return std::optional<NativeLayer>(std::move(*native));
}

} // namespace overlayd
