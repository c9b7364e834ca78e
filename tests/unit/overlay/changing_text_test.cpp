// A token text whose string changes on every frame (a frame counter) is drawn straight into each frame from the
// glyph cache; one that holds still goes back to a cached layer. Both must show the same text: a counter's frame is
// compared with a fresh renderer's cached frame for the same frame number, in every format, at an odd size with
// padded strides.
#include <algorithm>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "overlay/glyph_stamps.h"
#include "scene_fixture.h"

namespace overlayd {
namespace {

using test::TestFrame;

constexpr unsigned kWidth = 161, kHeight = 67, kPadding = 6;
// The cached layer composites the background box and the glyphs before it blends, the direct path blends one and
// then the other: a code of rounding apart, more only where both share a chroma sample at the glyphs' edges.
constexpr int kCloseCodes = 3;
constexpr double kMaxFarFraction = 0.01;

// The demo scene (with its "frame {frame}" text) in one format, and frames blended with it.
struct CounterScene {
    explicit CounterScene(std::string name) : format(std::move(name)) {}

    std::unique_ptr<SceneRenderer> renderer() const { return test::makeRenderer(scene, camera, stream); }
    // `renderer`'s blend of frame number `sequence` on grey.
    TestFrame blend(SceneRenderer &renderer, uint64_t sequence) const
    {
        TestFrame frame = test::greyFrame(format, kWidth, kHeight, kPadding);
        FrameMetadata metadata;
        metadata.sequence = sequence;
        EXPECT_TRUE(renderer.blend(frame.view(), metadata, 30.0));
        EXPECT_TRUE(frame.guardIntact());
        return frame;
    }
    // A fresh renderer's frame: the text from its cached layer.
    TestFrame cached(uint64_t sequence) const
    {
        auto fresh = renderer();
        TestFrame frame = blend(*fresh, sequence);
        EXPECT_EQ(fresh->textsDrawnDirectly(), 0u);
        return frame;
    }

    std::string format;
    OverlayScene scene = test::demoScene(true);
    Camera camera = test::groundCamera(kWidth, kHeight);
    StreamFormat stream = test::streamFormat(format, kWidth, kHeight);
};

// Pixels that differ by more than kCloseCodes in any channel, read back as BGR.
int farPixels(const TestFrame &a, const TestFrame &b, unsigned width = kWidth, unsigned height = kHeight)
{
    cv::Mat diff;
    cv::absdiff(test::toBgr(a), test::toBgr(b), diff);
    cv::Mat worst;
    cv::reduce(diff.reshape(1, int(width * height)), worst, 1, cv::REDUCE_MAX);
    return cv::countNonZero(worst > kCloseCodes);
}

class ChangingText : public testing::TestWithParam<std::string>
{};

TEST_P(ChangingText, ACounterDrawnIntoTheFrameMatchesItsCachedLayer)
{
    const CounterScene scene(GetParam());
    auto counting = scene.renderer();
    for (uint64_t sequence = 1; sequence <= 12; ++sequence) {
        const TestFrame direct = scene.blend(*counting, sequence);
        // The first frame renders a layer (a text may hold still); from the second new string on it is drawn.
        ASSERT_EQ(counting->textsDrawnDirectly(), sequence >= 2 ? 1u : 0u) << sequence;
        if (sequence < 2)
            continue;
        EXPECT_LE(farPixels(direct, scene.cached(sequence)), kMaxFarFraction * kWidth * kHeight)
            << scene.format << " frame " << sequence;
        // The text is there: the frames of two numbers differ (a direct path that drew nothing would match nothing).
        EXPECT_GT(farPixels(direct, scene.cached(sequence + 1)), 10) << scene.format << " frame " << sequence;
    }
}

// A counter that stops (a slot set once) is blended from a layer again: byte-identical to a fresh renderer's.
TEST_P(ChangingText, ATextThatHoldsStillReturnsToItsLayer)
{
    const CounterScene scene(GetParam());
    auto counting = scene.renderer();
    for (uint64_t sequence = 1; sequence <= 3; ++sequence)
        scene.blend(*counting, sequence);
    ASSERT_EQ(counting->textsDrawnDirectly(), 1u);
    const TestFrame cached = scene.cached(3);
    for (int i = 0; i < 2; ++i) {
        const TestFrame again = scene.blend(*counting, 3);
        EXPECT_EQ(counting->textsDrawnDirectly(), 0u);
        EXPECT_EQ(again.bytes, cached.bytes) << scene.format << " frame " << i;
    }
}

// A text whose glyphs keep landing on new places (a message set at run time, every frame another) keeps at most
// kMaxGlyphStamps stamps, and still draws every glyph.
TEST(GlyphStamps, AreBoundedAndDrawEveryGlyph)
{
    const StreamFormat stream = test::streamFormat("NV12", 640, 360);
    GlyphStamps stamps(stream, Colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited});
    TextRenderer text;
    TextItem item;
    item.sizePx = 20.0;
    item.colour = kWhite;
    size_t most = 0;
    for (int i = 0; i < 60; ++i) {
        item.text.clear();
        for (int k = 0; k < 40; ++k)
            item.text += char(33 + (i * 7 + k * 13) % 94); // printable ASCII, a different mix each time
        TestFrame frame = test::greyFrame("NV12", 640, 360, 0), before = frame;
        ASSERT_TRUE(stamps.blend(text, item, {4, 4 + 5 * i}, {0, 0, 640, 360}, frame.view()));
        most = std::max(most, stamps.size());
        EXPECT_GT(farPixels(frame, before, 640, 360), 40 * 10) << i; // every one of the 40 glyphs shows
    }
    EXPECT_LE(most, kMaxGlyphStamps);
    EXPECT_GT(most, kMaxGlyphStamps / 2) << "the texts above did not make enough stamps: the test checks nothing";
}

INSTANTIATE_TEST_SUITE_P(AllFormats, ChangingText, testing::ValuesIn(test::formatNames()), test::formatName);

} // namespace
} // namespace overlayd
