// SPDX-License-Identifier: Apache-2.0
// Text coverage from a glyph cache: DejaVu Sans through FreeType, each glyph rendered once per size and kept as
// coverage, so a string that changes every frame (a frame counter, a timestamp) costs a copy of its glyphs, not a
// FreeType rendering. OpenCV's Hershey font when the font is missing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <opencv2/core.hpp>

namespace overlayd {

inline constexpr const char *kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// The glyph cache's bound (coverage bytes of every size and glyph kept). A scene that asks for more (many sizes of
// many scripts) starts the cache over, which costs time, not memory.
inline constexpr size_t kMaxGlyphCacheBytes = size_t(16) << 20;

class TextRenderer
{
public:
    // Falls back to the Hershey font, with a warning on stderr (once per process), when fontPath cannot be loaded.
    explicit TextRenderer(const std::string &fontPath = kDefaultFontPath);
    ~TextRenderer();
    TextRenderer(const TextRenderer &) = delete;
    TextRenderer &operator=(const TextRenderer &) = delete;

    // The text's box: width, and height split at the baseline into ascent and descent. With FreeType the height is
    // the font's (its ascender and descender at this size, widened only by glyphs that reach beyond them), so a
    // box does not jump when the digits of a counter change.
    struct Box {
        int width = 0, ascent = 0, descent = 0;
        int height() const { return ascent + descent; }
    };
    // Anti-aliased and 1-bit glyphs can differ in width by a pixel: a box is measured for the way it is drawn.
    Box measure(const std::string &text, double sizePx, bool antialias = true) const;
    // The coverage (0..255) of the text drawn in its box, CV_8UC1 of the box's size, composed from cached glyphs the
    // way OpenCV's FreeType module composes them (a glyph over the ones before it). The matrix shares the renderer's
    // scratch: valid until the next call.
    cv::Mat render(const std::string &text, double sizePx, bool antialias) const;

    // One glyph of a string as render() places it: its coverage's top-left corner in the string's box (x right,
    // y down), and the code point it shows.
    struct PlacedGlyph {
        char32_t codepoint = 0;
        int x = 0, y = 0, width = 0, rows = 0;
        const uint8_t *coverage = nullptr; // rows x width, in the glyph cache
    };
    // The glyphs of `text` with ink, in drawing order; valid until the next call. Empty without FreeType.
    const std::vector<PlacedGlyph> &placeGlyphs(const std::string &text, double sizePx, bool antialias) const;

    bool usesFreeType() const { return face_ != nullptr; }
    // The coverage bytes the glyph cache holds, for tests and footprint figures.
    size_t cachedGlyphBytes() const { return cachedBytes_; }

private:
    struct Glyph {
        int left = 0, top = 0; // the bitmap's offset from the pen on the baseline (x right, y up)
        int width = 0, rows = 0;
        int advance = 0; // whole pixels, as OpenCV's FreeType module steps the pen
        std::vector<uint8_t> coverage;
    };
    struct Layout {
        Box box;
        int penX = 0; // where the first glyph's pen starts in the box
    };

    const Glyph &glyph(char32_t codepoint, int pixelHeight, bool antialias) const;
    // Decodes UTF-8 into glyphs_ (pointers into the cache) and measures their box.
    Layout layOut(const std::string &text, int pixelHeight, bool antialias) const;
    // Lays out `text` and fills placed_ with its glyphs; returns its box.
    Box place(const std::string &text, double sizePx, bool antialias) const;
    cv::Mat renderHershey(const std::string &text, double sizePx, bool antialias) const;

    struct FaceHandle;
    FaceHandle *face_ = nullptr; // FreeType's library and face; none when the font could not be loaded
    mutable int faceHeight_ = 0; // the pixel size the face is set to
    mutable std::unordered_map<uint64_t, Glyph> cache_;
    mutable size_t cachedBytes_ = 0;
    mutable std::vector<const Glyph *> glyphs_; // scratch: the glyphs of the string being laid out
    mutable std::vector<char32_t> codepoints_;  // and their code points
    mutable std::vector<PlacedGlyph> placed_;   // scratch: what placeGlyphs() returns
    mutable std::vector<uint8_t> scratch_;      // the coverage render() returns
};

} // namespace overlayd
