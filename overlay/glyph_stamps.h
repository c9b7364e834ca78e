// SPDX-License-Identifier: Apache-2.0
// GlyphStamps: the glyphs of a text that changes every frame (a frame counter), each kept as a small native layer
// at the place it was drawn. The digits of a counter land on a few places only, so after the first frames every
// glyph is a cached blend: only the glyphs whose stamp is new are rasterized and converted.
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_map>

#include <glm/vec2.hpp>

#include "media/stream.h"
#include "overlay/blend/native_layer.h"
#include "overlay/raster/coverage.h"
#include "overlay/raster/text_renderer.h"
#include "overlay/shapes/primitives.h"

namespace overlayd {

// How many stamps a text keeps (a counter needs its prefix's glyphs and ten digits per place); a text whose glyphs
// keep landing on new places starts over, which costs time, not memory.
inline constexpr size_t kMaxGlyphStamps = 512;

// A frame-pixel box widened to whole macropixels of `format` and cut to the frame: where a native layer can be placed
// (LayerPlacement's rule).
LayerRect macropixelAligned(LayerRect box, const PixelFormatInfo &format, unsigned frameWidth, unsigned frameHeight);

class GlyphStamps
{
public:
    GlyphStamps(const StreamFormat &format, Colorimetry colorimetry) : format_(format), colorimetry_(colorimetry) {}

    // Blends item's glyphs (not its background) onto the frame, its box's top-left corner at `origin` (frame
    // pixels); nothing outside `clip`. Stamps are made on a glyph's first appearance at its place.
    Status blend(const TextRenderer &text, const TextItem &item, glm::ivec2 origin, const LayerRect &clip,
                 const FrameView &frame);
    // The place or colour of what is drawn changed (a new viewport): every stamp is made again.
    void clear() { stamps_.clear(); }
    size_t size() const { return stamps_.size(); }

private:
    Result<std::optional<NativeLayer>> make(const TextRenderer::PlacedGlyph &glyph, glm::ivec2 at, Rgba colour,
                                            const LayerRect &clip) const;

    StreamFormat format_;
    Colorimetry colorimetry_;
    std::unordered_map<uint64_t, std::optional<NativeLayer>> stamps_; // by code point and place
};

} // namespace overlayd
