// SPDX-License-Identifier: Apache-2.0
// TextRenderer: FreeType renders a glyph the first time a (size, anti-aliasing, code point) is asked for; a string
// is then the copy of its cached glyphs into a scratch box. The placement and the composition are OpenCV's FreeType
// module's (pen in whole pixels, bearings rounded down, each glyph blended over what is there), which the module's
// own output checks in tests, but without its HarfBuzz pass: that pass only chose glyphs (OpenCV ignores the
// positions it computes), and a code point's glyph from the font's character map is the same for the scripts a
// label uses.
#include "overlay/raster/text_renderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>

#include <ft2build.h>
#include FT_FREETYPE_H
#include <opencv2/imgproc.hpp>

namespace overlayd {

struct TextRenderer::FaceHandle {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
};

namespace {

// Hershey Simplex is 22 units tall at scale 1 (cap height about 16); this scale gives a cap height close to
// DejaVu's at the same requested size.
double hersheyScale(double sizePx)
{
    return 0.8 * sizePx / 22.0;
}

int fontHeight(double sizePx)
{
    return std::max(1, int(std::lround(sizePx)));
}

void warnOnce(const std::string &fontPath)
{
    static std::atomic<bool> warned{false};
    if (!warned.exchange(true))
        std::fprintf(stderr, "overlayd: warning: cannot load font %s; text falls back to OpenCV's Hershey font\n",
                     fontPath.c_str());
}

// The next code point of UTF-8 text at `at` (advanced past it); a malformed sequence is one U+FFFD per byte.
char32_t nextCodepoint(const std::string &text, size_t &at)
{
    const auto byte = [&](size_t i) {
        return uint8_t(text[i]);
    };
    const uint8_t lead = byte(at++);
    if (lead < 0x80)
        return lead;
    const int extra = lead >= 0xf0 && lead < 0xf5 ? 3 : lead >= 0xe0 ? 2 : lead >= 0xc2 && lead < 0xe0 ? 1 : -1;
    if (extra < 0 || at + size_t(extra) > text.size())
        return 0xfffd;
    char32_t cp = lead & (0x3f >> extra);
    for (int i = 0; i < extra; ++i) {
        if ((byte(at + size_t(i)) & 0xc0) != 0x80)
            return 0xfffd;
        cp = (cp << 6) | (byte(at + size_t(i)) & 0x3f);
    }
    at += size_t(extra);
    return cp;
}

// OpenCV's blend of a glyph's coverage c over d, white on black, in its own arithmetic (double, truncated).
uint8_t over(uint8_t d, uint8_t c)
{
    const double alpha = double(c) / 255.0;
    return uint8_t(255.0 * alpha + double(d) * (1.0 - alpha));
}

// over(0, c) for every c: glyphs seldom overlap, so nearly every pixel is a look-up.
struct OverBlack {
    std::array<uint8_t, 256> table;
    OverBlack()
    {
        for (int c = 0; c < 256; ++c)
            table[size_t(c)] = over(0, uint8_t(c));
    }
};
const OverBlack kOverBlack;

} // namespace

TextRenderer::TextRenderer(const std::string &fontPath)
{
    auto *handle = new FaceHandle;
    if (FT_Init_FreeType(&handle->library) == 0 &&
        FT_New_Face(handle->library, fontPath.c_str(), 0, &handle->face) == 0) {
        face_ = handle;
        return;
    }
    if (handle->library)
        FT_Done_FreeType(handle->library);
    delete handle;
    warnOnce(fontPath);
}

TextRenderer::~TextRenderer()
{
    if (!face_)
        return;
    FT_Done_Face(face_->face);
    FT_Done_FreeType(face_->library);
    delete face_;
}

const TextRenderer::Glyph &TextRenderer::glyph(char32_t codepoint, int pixelHeight, bool antialias) const
{
    const uint64_t key = uint64_t(codepoint) | uint64_t(pixelHeight) << 32 | uint64_t(antialias) << 63;
    if (const auto it = cache_.find(key); it != cache_.end())
        return it->second;
    Glyph &glyph = cache_[key];
    FT_Face face = face_->face; // set to pixelHeight by layOut
    // A code point the font lacks is its .notdef box (glyph 0), as OpenCV's module shows it.
    if (FT_Load_Glyph(face, FT_Get_Char_Index(face, FT_ULong(codepoint)), FT_LOAD_DEFAULT) != 0 ||
        FT_Render_Glyph(face->glyph, antialias ? FT_RENDER_MODE_NORMAL : FT_RENDER_MODE_MONO) != 0)
        return glyph; // nothing to draw and no advance: a glyph FreeType cannot render is left out
    const FT_GlyphSlot slot = face->glyph;
    const FT_Bitmap &bitmap = slot->bitmap;
    glyph.left = int(slot->metrics.horiBearingX >> 6);
    glyph.top = int(slot->metrics.horiBearingY >> 6);
    glyph.advance = int(slot->advance.x >> 6);
    glyph.width = int(bitmap.width);
    glyph.rows = int(bitmap.rows);
    glyph.coverage.resize(size_t(glyph.width) * size_t(glyph.rows));
    for (int y = 0; y < glyph.rows; ++y) {
        const uint8_t *row = bitmap.buffer + ptrdiff_t(y) * bitmap.pitch;
        uint8_t *out = glyph.coverage.data() + size_t(y) * size_t(glyph.width);
        for (int x = 0; x < glyph.width; ++x)
            out[x] = antialias ? row[x] : ((row[x >> 3] >> (7 - (x & 7))) & 1) * 255;
    }
    cachedBytes_ += glyph.coverage.size() + sizeof(Glyph);
    return glyph;
}

TextRenderer::Layout TextRenderer::layOut(const std::string &text, int pixelHeight, bool antialias) const
{
    if (cachedBytes_ > kMaxGlyphCacheBytes) { // here, never while glyphs_ holds pointers into the cache
        cache_.clear();
        cachedBytes_ = 0;
    }
    glyphs_.clear();
    codepoints_.clear();
    FT_Face face = face_->face;
    if (faceHeight_ != pixelHeight) { // the metrics below are the size's, and so are new glyphs
        if (FT_Set_Pixel_Sizes(face, FT_UInt(pixelHeight), FT_UInt(pixelHeight)) != 0)
            return {};
        faceHeight_ = pixelHeight;
    }
    int pen = 0, inkLeft = 0, inkRight = 0, top = 0, bottom = 0;
    for (size_t at = 0; at < text.size();) {
        const char32_t codepoint = nextCodepoint(text, at);
        const Glyph &g = glyph(codepoint, pixelHeight, antialias);
        glyphs_.push_back(&g);
        codepoints_.push_back(codepoint);
        if (g.width > 0 && g.rows > 0) {
            inkLeft = std::min(inkLeft, pen + g.left);
            inkRight = std::max(inkRight, pen + g.left + g.width);
            top = std::max(top, g.top);
            bottom = std::max(bottom, g.rows - g.top);
        }
        pen += g.advance;
    }
    if (glyphs_.empty())
        return {};
    const FT_Size_Metrics &metrics = face->size->metrics;
    const int ascender = int(metrics.ascender >> 6), descender = int(-metrics.descender >> 6);
    // One spare pixel on each side, as the box always had.
    Layout layout;
    layout.penX = 1 - inkLeft;
    layout.box.width = layout.penX + std::max(inkRight, pen) + 1;
    layout.box.ascent = std::max(ascender, top) + 1;
    layout.box.descent = std::max(descender, bottom) + 1;
    return layout;
}

TextRenderer::Box TextRenderer::measure(const std::string &text, double sizePx, bool antialias) const
{
    if (!face_) {
        int baseline = 0;
        const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, hersheyScale(sizePx), 1, &baseline);
        return {size.width + 2, size.height + 1, baseline + 1};
    }
    return layOut(text, fontHeight(sizePx), antialias).box;
}

cv::Mat TextRenderer::render(const std::string &text, double sizePx, bool antialias) const
{
    if (!face_)
        return renderHershey(text, sizePx, antialias);
    const Box box = place(text, sizePx, antialias);
    const int width = std::max(box.width, 1), height = std::max(box.height(), 1);
    scratch_.assign(size_t(width) * size_t(height), 0);
    for (const PlacedGlyph &g : placed_) {
        for (int y = 0; y < g.rows; ++y) {
            uint8_t *out = scratch_.data() + size_t(g.y + y) * size_t(width) + g.x;
            const uint8_t *in = g.coverage + size_t(y) * size_t(g.width);
            for (int x = 0; x < g.width; ++x) {
                if (in[x] != 0)
                    out[x] = out[x] == 0 ? kOverBlack.table[in[x]] : over(out[x], in[x]);
            }
        }
    }
    return cv::Mat(height, width, CV_8UC1, scratch_.data());
}

const std::vector<TextRenderer::PlacedGlyph> &TextRenderer::placeGlyphs(const std::string &text, double sizePx,
                                                                        bool antialias) const
{
    placed_.clear();
    if (face_)
        place(text, sizePx, antialias);
    return placed_;
}

TextRenderer::Box TextRenderer::place(const std::string &text, double sizePx, bool antialias) const
{
    const Layout layout = layOut(text, fontHeight(sizePx), antialias);
    placed_.clear();
    int pen = layout.penX;
    for (size_t i = 0; i < glyphs_.size(); ++i) {
        const Glyph &g = *glyphs_[i];
        if (g.width > 0 && g.rows > 0)
            placed_.push_back(
                {codepoints_[i], pen + g.left, layout.box.ascent - g.top, g.width, g.rows, g.coverage.data()});
        pen += g.advance;
    }
    return layout.box;
}

cv::Mat TextRenderer::renderHershey(const std::string &text, double sizePx, bool antialias) const
{
    const Box box = measure(text, sizePx);
    cv::Mat bgr = cv::Mat::zeros(std::max(box.height(), 1), std::max(box.width, 1), CV_8UC3);
    cv::putText(bgr, text, cv::Point(1, box.ascent), cv::FONT_HERSHEY_SIMPLEX, hersheyScale(sizePx),
                cv::Scalar::all(255), 1, antialias ? cv::LINE_AA : cv::LINE_8);
    cv::Mat coverage;
    cv::extractChannel(bgr, coverage, 0);
    return coverage;
}

} // namespace overlayd
