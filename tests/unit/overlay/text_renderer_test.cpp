// SPDX-License-Identifier: Apache-2.0
// TextRenderer composes strings from glyphs it renders once. The reference is OpenCV's FreeType module (what the
// renderer used before the glyph cache), drawing the same string white on black with the pen at the same place:
// the coverage must be the same, byte for byte.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/freetype.hpp>
#include <opencv2/imgproc.hpp>

#include "overlay/raster/text_renderer.h"

namespace overlayd {
namespace {

// Labels, counters and timestamps as scenes write them; none starts with a glyph that reaches left of its pen
// (the renderer then starts the pen one pixel in, where the reference draws it).
const std::vector<std::string> kTexts = {
    "frame 12345",     "2026-11-27 00:48:16", "origin", "5 m",         "Reverse: 1.5 m", "X",
    "f i f l f f",     "AVAWAY To",           "Wy.",    "Überhöhe ñ°", "{x}[y](z) | _",  "mm  gap  ",
    "100 km/h ±0.5 %", "Δt = 3 µs",
};

// OpenCV's FreeType module's coverage of `text` in a box of `box`'s size, the pen starting at x = 1 on the
// baseline at row box.ascent (it places the baseline fontHeight below the point it is given).
cv::Mat reference(cv::freetype::FreeType2 &freeType, const std::string &text, int fontHeight, bool antialias,
                  const TextRenderer::Box &box)
{
    cv::Mat bgr = cv::Mat::zeros(box.height(), box.width, CV_8UC3);
    freeType.putText(bgr, text, {1, box.ascent - fontHeight}, fontHeight, cv::Scalar::all(255), -1,
                     antialias ? cv::LINE_AA : cv::LINE_8, false);
    cv::Mat coverage;
    cv::extractChannel(bgr, coverage, 0);
    return coverage;
}

TEST(TextRenderer, ComposesGlyphsAsOpenCvsFreeTypeModuleDraws)
{
    TextRenderer renderer;
    ASSERT_TRUE(renderer.usesFreeType()) << "the font " << kDefaultFontPath << " is a dependency (fonts-dejavu-core)";
    auto freeType = cv::freetype::createFreeType2();
    freeType->loadFontData(kDefaultFontPath, 0);
    int compared = 0;
    for (int size : {9, 12, 16, 24, 37, 64}) {
        for (bool antialias : {true, false}) {
            for (const std::string &text : kTexts) {
                const TextRenderer::Box box = renderer.measure(text, size, antialias);
                const cv::Mat ours = renderer.render(text, size, antialias).clone();
                ASSERT_EQ(ours.rows, box.height());
                ASSERT_EQ(ours.cols, box.width);
                const cv::Mat theirs = reference(*freeType, text, size, antialias, box);
                const int differing = cv::countNonZero(ours != theirs);
                EXPECT_EQ(differing, 0) << "\"" << text << "\" at " << size << " px, antialias " << antialias;
                EXPECT_GT(cv::countNonZero(ours), 0) << text;
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, 6 * 2 * int(kTexts.size()));
}

// A glyph that reaches left of its pen (j's hook) or above the font's ascender is inside the box, not cut off: the
// box holds all of the ink OpenCV draws on a canvas with room around it.
TEST(TextRenderer, TheBoxHoldsAllTheInk)
{
    TextRenderer renderer;
    ASSERT_TRUE(renderer.usesFreeType());
    auto freeType = cv::freetype::createFreeType2();
    freeType->loadFontData(kDefaultFontPath, 0);
    for (const std::string &text : {std::string("jig"), std::string("ÅÉÎ Ǻ"), std::string("_j_"), std::string("f")}) {
        const int size = 30;
        cv::Mat roomy = cv::Mat::zeros(200, 400, CV_8UC3);
        freeType->putText(roomy, text, {100, 50}, size, cv::Scalar::all(255), -1, cv::LINE_AA, false);
        cv::Mat channel;
        cv::extractChannel(roomy, channel, 0);
        const cv::Mat ours = renderer.render(text, size, true);
        EXPECT_EQ(cv::sum(ours)[0], cv::sum(channel)[0]) << text;
        // One spare pixel on every side.
        EXPECT_EQ(cv::countNonZero(ours.row(0)), 0) << text;
        EXPECT_EQ(cv::countNonZero(ours.row(ours.rows - 1)), 0) << text;
        EXPECT_EQ(cv::countNonZero(ours.col(0)), 0) << text;
        EXPECT_EQ(cv::countNonZero(ours.col(ours.cols - 1)), 0) << text;
    }
}

// The box's height is the font's line, so a counter's background does not jump as its digits change; its width
// follows the pen.
TEST(TextRenderer, TheBoxOfACounterKeepsItsHeight)
{
    TextRenderer renderer;
    ASSERT_TRUE(renderer.usesFreeType());
    const TextRenderer::Box ones = renderer.measure("frame 111", 24), eights = renderer.measure("frame 888", 24);
    EXPECT_EQ(ones.ascent, eights.ascent);
    EXPECT_EQ(ones.descent, eights.descent);
    EXPECT_EQ(renderer.measure("a", 24).height(), renderer.measure("g", 24).height());
    // DejaVu's digits share one advance: the same width too.
    EXPECT_EQ(ones.width, eights.width);
    EXPECT_LT(renderer.measure("frame 1", 24).width, ones.width);
}

// Malformed UTF-8 is drawn as replacement characters, one per bad byte, never read past the string's end.
TEST(TextRenderer, MalformedUtf8IsDrawnAsReplacementCharacters)
{
    TextRenderer renderer;
    ASSERT_TRUE(renderer.usesFreeType());
    const TextRenderer::Box two = renderer.measure("\xef\xbf\xbd\xef\xbf\xbd", 20); // two U+FFFD
    EXPECT_EQ(renderer.measure("\xff\xc3", 20).width, two.width); // a byte no UTF-8 has, a lead byte at the end
    EXPECT_EQ(renderer.measure("\xe2\x82", 20).width, two.width); // a cut sequence: two bad bytes
}

// Each glyph is rendered once: drawing more strings from the same glyphs adds nothing to the cache, and the cache
// starts over once it holds more than its bound.
TEST(TextRenderer, TheGlyphCacheIsReusedAndBounded)
{
    TextRenderer renderer;
    ASSERT_TRUE(renderer.usesFreeType());
    renderer.render("frame 0123456789", 24, true);
    const size_t digits = renderer.cachedGlyphBytes();
    EXPECT_GT(digits, 0u);
    for (int i = 0; i < 1000; ++i)
        renderer.render("frame " + std::to_string(i * 7919), 24, true);
    EXPECT_EQ(renderer.cachedGlyphBytes(), digits);

    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    size_t most = 0;
    for (int size = 200; size <= 1000; size += 100) {
        TextRenderer alone;
        alone.render(alphabet, size, true);
        const size_t oneString = alone.cachedGlyphBytes(); // what this size adds to a cache that lacks it
        renderer.render(alphabet, size, true);
        EXPECT_LE(renderer.cachedGlyphBytes(), kMaxGlyphCacheBytes + oneString) << size;
        most = std::max(most, renderer.cachedGlyphBytes());
    }
    EXPECT_GT(most, kMaxGlyphCacheBytes) << "the sizes above did not reach the bound: the test checks nothing";
}

} // namespace
} // namespace overlayd
