// SPDX-License-Identifier: Apache-2.0
// A token text (a frame counter) is blended as its background box's layer and one stamp per glyph and place. It must
// show what the same text written out shows, drawn the other way (the world layers' RGBA canvas, converted once),
// for each frame number, in every format, at an odd size with padded strides.
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
// The canvas composites the background box and the glyphs before it converts, the stamps blend one after the
// other: a code of rounding apart, more only where two share a chroma sample at the glyphs' edges.
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
    // The reference: the same scene with the counter's text written out ("frame 7"), a text without tokens, which
    // is drawn with the world layers on their RGBA canvas and converted once.
    TestFrame written(uint64_t sequence) const
    {
        OverlayScene fixed = scene;
        for (Annotation &a : fixed.annotations)
            if (auto *text = std::get_if<ScreenTextShape>(&a.shape); text && text->text == "frame {frame}")
                text->text = "frame " + std::to_string(sequence);
        auto still = test::makeRenderer(fixed, camera, stream);
        return blend(*still, 0);
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

TEST_P(ChangingText, ACounterOfStampsMatchesItsTextWrittenOut)
{
    const CounterScene scene(GetParam());
    auto counting = scene.renderer();
    for (uint64_t sequence : {1, 2, 3, 9, 10, 11, 12, 99, 100, 101, 7, 1234}) {
        const TestFrame stamped = scene.blend(*counting, sequence);
        EXPECT_LE(farPixels(stamped, scene.written(sequence)), kMaxFarFraction * kWidth * kHeight)
            << scene.format << " frame " << sequence;
        // The text is there: the frames of two numbers differ (stamps that drew nothing would match nothing).
        EXPECT_GT(farPixels(stamped, scene.written(sequence + 1)), 10) << scene.format << " frame " << sequence;
    }
}

// Stamps are blended, never changed: a number shown again gives the same bytes as the first time, whatever came
// between (here: other numbers, a wider box and back).
TEST_P(ChangingText, ANumberShownAgainGivesTheSameBytes)
{
    const CounterScene scene(GetParam());
    auto counting = scene.renderer();
    const TestFrame first = scene.blend(*counting, 42);
    for (uint64_t sequence : {43, 44, 142, 1042, 41})
        scene.blend(*counting, sequence);
    EXPECT_EQ(scene.blend(*counting, 42).bytes, first.bytes) << scene.format;
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
