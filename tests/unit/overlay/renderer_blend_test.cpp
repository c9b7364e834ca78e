// SPDX-License-Identifier: Apache-2.0
// The renderer end to end in every format: colours, partial alpha, untouched bytes, layers, token text, errors.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "scene_fixture.h"

namespace overlayd {
namespace {

using test::annotation;
using test::TestFrame;

constexpr int kYuvTolerance = 3; // one code of Y/Cb/Cr rounding moves a converted channel by up to ~2 (see
                                 // blend_colour_test.cpp)
const Colorimetry kBt601Limited{YcbcrMatrix::Bt601, ColourRange::Limited};

class RendererFormat : public testing::TestWithParam<std::string>
{};

// Opaque 6 px horizontal lines (screen crosshairs with a long horizontal arm) in red, green, blue, white and black
// on mid-grey; the colour at each line's centre, read back through OpenCV's converters.
TEST_P(RendererFormat, OpaqueLineColours)
{
    const std::string &format = GetParam();
    const Rgba colours[] = {kRed, kGreen, kBlue, kWhite, {0, 0, 0, 255}};
    OverlayScene scene;
    for (int i = 0; i < 5; ++i)
        scene.annotations.push_back(
            annotation("line", CrosshairShape{glm::dvec2(60.0, 20.5 + 20 * i), 80.0}, colours[i], 6.0));
    TestFrame frame = test::makeFrame(format, 120, 110, 10);
    test::fillRgb(frame, kBt601Limited, 128, 128, 128);
    auto renderer = test::makeRenderer(scene, test::groundCamera(120, 110), test::streamFormat(format, 120, 110));
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    ASSERT_TRUE(frame.guardIntact());
    const cv::Mat bgr = test::toBgr(frame);
    const bool rgb = test::format(format).encoding == ColourEncoding::Rgb;
    for (int i = 0; i < 5; ++i) {
        const cv::Vec3b got = bgr.at<cv::Vec3b>(20 + 20 * i, 30); // rows 20 and 21 are fully inside the line
        if (format == "GREY") {                                   // the luma code itself, BT.601 limited range
            const double luma = 16 + 219.0 / 255 * (0.299 * colours[i].r + 0.587 * colours[i].g + 0.114 * colours[i].b);
            EXPECT_NEAR(frame.plane(0)[(20 + 20 * i) * frame.stride(0) + 30], luma, 1.0) << "line " << i;
            continue;
        }
        const int tolerance = rgb ? 0 : kYuvTolerance;
        EXPECT_NEAR(got[2], colours[i].r, tolerance) << "line " << i;
        EXPECT_NEAR(got[1], colours[i].g, tolerance) << "line " << i;
        EXPECT_NEAR(got[0], colours[i].b, tolerance) << "line " << i;
    }
}

// Every byte that changed belongs to a pixel (or macropixel) that some layer covers; padding never changes.
TEST_P(RendererFormat, UntouchedOutsideCoverageWithStrideAndOddSize)
{
    const std::string &format = GetParam();
    const unsigned width = 101, height = 67;
    OverlayScene scene = test::demoScene(false);
    scene.annotations.push_back(annotation("label", LabelShape{{0.0, 0.0, 0.0}, "Ag", {3.0, 3.0}, 12.0}, kWhite));
    TestFrame frame = test::makeFrame(format, width, height, 6);
    test::fillRgb(frame, kBt601Limited, 90, 140, 60);
    const std::vector<uint8_t> before = frame.bytes;
    auto renderer =
        test::makeRenderer(scene, test::groundCamera(width, height), test::streamFormat(format, width, height));
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    ASSERT_TRUE(frame.guardIntact());

    cv::Mat covered = cv::Mat::zeros(int(height), int(width), CV_8UC1);
    for (const std::string &name : renderer->layerNames())
        covered = cv::max(covered, test::layerAlpha(*renderer->layerPixels(name)));
    ASSERT_GT(cv::countNonZero(covered), 300);
    size_t changed = 0;
    const PixelFormatInfo &info = test::format(format);
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        for (unsigned row = 0; row < info.planeHeight(p, height); ++row) {
            for (unsigned col = 0; col < frame.stride(p); ++col) {
                const size_t at = frame.layout.planes[p].offset + size_t(row) * frame.stride(p) + col;
                if (frame.bytes[at] == before[at])
                    continue;
                ++changed;
                const std::vector<cv::Point> pixels = test::pixelsOfByte(frame, p, row, col);
                ASSERT_FALSE(pixels.empty()) << "padding byte changed: plane " << p << " row " << row << " col " << col;
                bool anyCovered = false;
                for (const cv::Point &q : pixels)
                    anyCovered = anyCovered || covered.at<uint8_t>(q) > 0;
                EXPECT_TRUE(anyCovered) << "plane " << p << " row " << row << " col " << col;
            }
        }
    }
    EXPECT_GT(changed, 300u);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RendererFormat, testing::ValuesIn(test::formatNames()), test::formatName);

// 50% white over black: a line's interior lands within one code of the exact blend in luma, chroma and RGB.
TEST(RendererAlpha, HalfWhiteLineOverBlack)
{
    for (const char *format : {"YUYV", "NV12", "YUV420", "RGB24", "XBGR32", "GREY"}) {
        OverlayScene scene;
        scene.annotations.push_back(
            annotation("line", CrosshairShape{glm::dvec2(40.0, 20.0), 60.0}, Rgba{255, 255, 255, 128}, 8.0));
        TestFrame frame = test::makeFrame(format, 80, 40, 0);
        test::fillRgb(frame, kBt601Limited, 0, 0, 0);
        auto renderer = test::makeRenderer(scene, test::groundCamera(80, 40), test::streamFormat(format, 80, 40));
        ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
        const double a = 128.0 / 255.0;
        const PixelFormatInfo &info = test::format(format);
        if (info.encoding == ColourEncoding::Rgb) {
            const uint8_t *px = frame.plane(0) + 20 * frame.stride(0) + 16 * info.planes[0].bytesPerGroup;
            EXPECT_NEAR(px[info.rOffset], 255 * a, 1.0) << format;
            EXPECT_NEAR(px[info.gOffset], 255 * a, 1.0) << format;
        } else if (info.layout == PixelLayout::PackedYuv422) {
            const uint8_t *group = frame.plane(0) + 20 * frame.stride(0) + 8 * 4; // pixels 16 and 17
            EXPECT_NEAR(group[info.yOffset[0]], 16 + 219 * a, 1.0) << format;
            EXPECT_NEAR(group[info.cbOffset], 128, 1.0) << format;
        } else {
            EXPECT_NEAR(frame.plane(0)[20 * frame.stride(0) + 16], 16 + 219 * a, 1.0) << format;
            if (info.numPlanes > 1) {
                EXPECT_NEAR(frame.plane(1)[10 * frame.stride(1) + 8], 128, 1.0) << format;
            }
        }
    }
}

TEST(RendererLayers, SwitchingALayerOffDropsExactlyItsAnnotations)
{
    const OverlayScene scene = test::demoScene(true);
    const Camera camera = test::groundCamera(160, 120);
    auto renderer = test::makeRenderer(scene, camera, test::streamFormat("NV12", 160, 120));
    EXPECT_EQ(renderer->layerNames(), (std::vector<std::string>{"grid", "default", "guide", "text"}));
    ASSERT_TRUE(renderer->setLayerEnabled("grid", false));
    EXPECT_FALSE(renderer->setLayerEnabled("nope", false));
    EXPECT_EQ(renderer->setLayerEnabled("nope", false).error().code, ErrorCode::InvalidArgument);

    OverlayScene withoutGrid = scene;
    std::erase_if(withoutGrid.annotations, [](const Annotation &a) { return a.style.layer == "grid"; });
    auto reference = test::makeRenderer(withoutGrid, camera, test::streamFormat("NV12", 160, 120));
    TestFrame a = test::makeFrame("NV12", 160, 120, 0), b = test::makeFrame("NV12", 160, 120, 0);
    test::fillRgb(a, kBt601Limited, 100, 100, 100);
    test::fillRgb(b, kBt601Limited, 100, 100, 100);
    ASSERT_TRUE(renderer->blend(a.view(), FrameMetadata{}, 30.0));
    ASSERT_TRUE(reference->blend(b.view(), FrameMetadata{}, 30.0));
    EXPECT_EQ(a.bytes, b.bytes);
}

TEST(RendererText, TokenTextFollowsTheFrame)
{
    OverlayScene scene;
    scene.annotations.push_back(annotation("stamp", ScreenTextShape{"#{frame}", {4.0, 4.0}, 16.0}, kWhite));
    auto renderer = test::makeRenderer(scene, test::groundCamera(96, 32), test::streamFormat("YUYV", 96, 32));
    const auto blendWith = [&](uint64_t sequence) {
        TestFrame frame = test::makeFrame("YUYV", 96, 32, 0);
        test::fillRgb(frame, kBt601Limited, 0, 0, 0);
        FrameMetadata metadata;
        metadata.sequence = sequence;
        EXPECT_TRUE(renderer->blend(frame.view(), metadata, 30.0));
        return frame.bytes;
    };
    const auto one = blendWith(1), eleven = blendWith(11), oneAgain = blendWith(1);
    EXPECT_NE(one, eleven);
    EXPECT_EQ(one, oneAgain);
}

// A {slot:NAME} shows what setSlotText gave it from the next frame on: the same pixels as that text written in the
// config, nothing before it is set; unknown slots and control characters are refused and change nothing.
TEST(RendererText, SlotTextShowsWhatWasSet)
{
    const auto blendScene = [](const std::string &text, const std::string &slotText) {
        OverlayScene scene;
        scene.annotations.push_back(annotation("gear", ScreenTextShape{text, {4.0, 4.0}, 16.0}, kWhite));
        auto renderer = test::makeRenderer(scene, test::groundCamera(96, 32), test::streamFormat("NV12", 96, 32));
        if (!slotText.empty()) {
            EXPECT_TRUE(renderer->setSlotText("gear", slotText));
        }
        EXPECT_FALSE(renderer->setSlotText("speed", "12"));
        EXPECT_FALSE(renderer->setSlotText("gear", "R\nD"));
        EXPECT_FALSE(renderer->setSlotText("gear", std::string(kMaxSlotTextBytes + 1, 'x')));
        TestFrame frame = test::makeFrame("NV12", 96, 32, 0);
        test::fillRgb(frame, kBt601Limited, 0, 0, 0);
        EXPECT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
        return frame.bytes;
    };
    EXPECT_EQ(blendScene("gear {slot:gear}", "R"), blendScene("gear R", ""));
    EXPECT_EQ(blendScene("gear {slot:gear}", ""), blendScene("gear ", ""));
    EXPECT_NE(blendScene("gear {slot:gear}", "D"), blendScene("gear R", ""));
}

TEST(RendererErrors, RefusesBadScenesAndMismatchedCameras)
{
    const Camera camera = test::groundCamera(64, 48);
    const StreamFormat format = test::streamFormat("NV12", 64, 48);
    const auto refused = [&](Annotation a) {
        OverlayScene scene;
        scene.annotations.push_back(std::move(a));
        auto result = SceneRenderer::create(scene, camera, format);
        return !result.ok() && result.error().code == ErrorCode::InvalidArgument &&
               result.error().message.find("\"bad\"") != std::string::npos;
    };
    Annotation unknownFrame = annotation("bad", AxesShape{});
    unknownFrame.frame = "nowhere";
    EXPECT_TRUE(refused(unknownFrame));
    EXPECT_TRUE(refused(annotation("bad", ScreenTextShape{"{nope}"})));
    EXPECT_TRUE(refused(annotation("bad", ScreenTextShape{"unbalanced {"})));
    EXPECT_TRUE(refused(annotation("bad", AxesShape{}, kWhite, 0.0)));
    EXPECT_TRUE(refused(annotation("bad", GridShape{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0.0})));
    EXPECT_TRUE(refused(annotation("bad", PolylineShape{{{0, 0, 0}, {NAN, 0, 0}}})));
    EXPECT_FALSE(SceneRenderer::create(OverlayScene{}, test::groundCamera(32, 48), format).ok());
    auto ok = SceneRenderer::create(test::demoScene(true), camera, format);
    ASSERT_TRUE(ok.ok()) << ok.error().message;
    EXPECT_FALSE((*ok)->setCamera(test::groundCamera(32, 48)).ok());
    EXPECT_TRUE((*ok)->setCamera(camera).ok());
    // The frame is checked once per blend (the layers then blend unchecked): another size or format is refused
    // and left as it was.
    for (TestFrame wrong : {test::makeFrame("YUYV", format.width, format.height, 0),
                            test::makeFrame(std::string(format.format->name), format.width + 2, format.height, 0)}) {
        const std::vector<uint8_t> before = wrong.bytes;
        EXPECT_FALSE((*ok)->blend(wrong.view(), FrameMetadata{}, 30.0).ok());
        EXPECT_EQ(wrong.bytes, before);
    }
}

} // namespace
} // namespace overlayd
