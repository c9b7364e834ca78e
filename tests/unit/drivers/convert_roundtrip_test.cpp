// SPDX-License-Identifier: Apache-2.0
// Round trips through every format and colorimetry, chroma averaging over a macropixel, and the BT.601/BT.709
// colour-bar code values every broadcast reference lists (hand-checked: e.g. BT.709 limited red is 63, 102, 240).
#include <gtest/gtest.h>

#include "media/convert/colour_convert.h"
#include "media/convert/frame_convert.h"
#include "media/convert/packing.h"
#include "test_util.h"

namespace overlayd {
namespace {

constexpr Colorimetry kColorimetries[] = {{YcbcrMatrix::Bt601, ColourRange::Limited},
                                          {YcbcrMatrix::Bt601, ColourRange::Full},
                                          {YcbcrMatrix::Bt709, ColourRange::Limited},
                                          {YcbcrMatrix::Bt709, ColourRange::Full}};

int worstDifference(const RgbImage &a, const RgbImage &b)
{
    int worst = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        worst = std::max(worst, std::abs(int(a.rgb[i]) - int(b.rgb[i])));
    return worst;
}

class RoundTrip : public testing::TestWithParam<std::string>
{};

// Uniform macropixels survive subsampling; what remains is 8-bit quantization: about 1.2 codes per step at limited
// range, spread by the matrix into at most 3 per channel (2 at full range).
TEST_P(RoundTrip, RgbThroughFormatAndBack)
{
    const PixelFormatInfo &info = test::format(GetParam());
    const bool grey = info.encoding == ColourEncoding::Yuv && info.cbOffset == kNoComponent;
    for (const auto &[w, h] : {std::pair{64u, 48u}, std::pair{37u, 29u}}) {
        const RgbImage image = test::blockyImage(w, h, 2, 2, w, grey);
        for (const Colorimetry colorimetry : kColorimetries) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + matrixName(colorimetry.matrix) + " " +
                         rangeName(colorimetry.range));
            FrameBuffer frame = test::makeFrame(GetParam(), w, h, 6);
            ASSERT_TRUE(rgbToFrame(image, colorimetry, frame.view()));
            auto back = frameToRgb(frame.view(), colorimetry);
            ASSERT_TRUE(back);
            const int allowed = info.encoding == ColourEncoding::Rgb        ? 0
                                : colorimetry.range == ColourRange::Limited ? 3
                                                                            : 2;
            EXPECT_LE(worstDifference(image, *back), allowed);
        }
    }
}

std::vector<std::string> allFormats()
{
    std::vector<std::string> names;
    for (const PixelFormatInfo &info : pixelFormats())
        names.emplace_back(info.name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RoundTrip, testing::ValuesIn(allFormats()),
                         [](const auto &test) { return test.param; });

TEST(RoundTrip, YcbcrSamplesSurvivePackingExactly)
{
    for (const PixelFormatInfo &info : pixelFormats()) {
        if (info.encoding != ColourEncoding::Yuv)
            continue;
        SCOPED_TRACE(std::string(info.name));
        YcbcrImage samples = ycbcrImageFor(info, 37, 29);
        for (size_t i = 0; i < samples.y.size(); ++i)
            samples.y[i] = uint8_t(i * 7);
        for (size_t i = 0; i < samples.cb.size(); ++i)
            samples.cb[i] = uint8_t(i * 3), samples.cr[i] = uint8_t(i * 5 + 1);
        FrameBuffer frame = test::makeFrame(std::string(info.name), 37, 29, 4);
        ASSERT_TRUE(packYcbcr(samples, frame.view()));
        auto back = unpackYcbcr(frame.view());
        ASSERT_TRUE(back);
        EXPECT_EQ(back->y, samples.y);
        EXPECT_EQ(back->cb, samples.cb);
        EXPECT_EQ(back->cr, samples.cr);
    }
}

// The chroma of a macropixel is the mean of its pixels' chroma: red and cyan average to grey (Cb = Cr = 128), and
// three red pixels with one black give the chroma of (191.25, 0, 0): Cb = 128 + 224/255 * (-0.299 * 191.25) / 1.772
// = 99.65 -> 100, Cr = 128 + 224/255 * (0.701 * 191.25) / 1.402 = 212.0 -> 212.
TEST(ChromaAveraging, MacropixelMeanInBt601Limited)
{
    RgbImage image = RgbImage::allocate(4, 2);
    const uint8_t pixels[8][3] = {{255, 0, 0},   {0, 255, 255}, {255, 0, 0}, {255, 0, 0},
                                  {0, 255, 255}, {255, 0, 0},   {255, 0, 0}, {0, 0, 0}};
    for (unsigned i = 0; i < 8; ++i)
        std::copy(pixels[i], pixels[i] + 3, &image.rgb[3 * i]);
    const YcbcrImage samples = rgbToYcbcr(image, {}, 2, 2, true);
    EXPECT_EQ(samples.cb[0], 128);
    EXPECT_EQ(samples.cr[0], 128);
    EXPECT_EQ(samples.cb[1], 100);
    EXPECT_EQ(samples.cr[1], 212);
    EXPECT_EQ(samples.y[0], 81);  // red, BT.601 limited
    EXPECT_EQ(samples.y[1], 170); // cyan
    EXPECT_EQ(samples.y[7], 16);  // black
}

struct Reference {
    Colorimetry colorimetry;
    uint8_t rgb[3];
    uint8_t ycbcr[3];
};

// 100% colours in the four colorimetries (ITU-R BT.601 / BT.709 tables; full range 709 red Cr is 255.5 -> 255).
constexpr Reference kReferences[] = {
    {{YcbcrMatrix::Bt601, ColourRange::Limited}, {255, 255, 255}, {235, 128, 128}},
    {{YcbcrMatrix::Bt601, ColourRange::Limited}, {0, 0, 0}, {16, 128, 128}},
    {{YcbcrMatrix::Bt601, ColourRange::Limited}, {255, 0, 0}, {81, 90, 240}},
    {{YcbcrMatrix::Bt601, ColourRange::Limited}, {0, 255, 0}, {145, 54, 34}},
    {{YcbcrMatrix::Bt601, ColourRange::Limited}, {0, 0, 255}, {41, 240, 110}},
    {{YcbcrMatrix::Bt709, ColourRange::Limited}, {255, 0, 0}, {63, 102, 240}},
    {{YcbcrMatrix::Bt709, ColourRange::Limited}, {0, 255, 0}, {173, 42, 26}},
    {{YcbcrMatrix::Bt709, ColourRange::Limited}, {0, 0, 255}, {32, 240, 118}},
    {{YcbcrMatrix::Bt709, ColourRange::Full}, {255, 0, 0}, {54, 99, 255}},
    {{YcbcrMatrix::Bt709, ColourRange::Full}, {255, 255, 255}, {255, 128, 128}},
    {{YcbcrMatrix::Bt601, ColourRange::Full}, {0, 0, 255}, {29, 255, 107}},
};

TEST(Colorimetry, ReferenceCodeValues)
{
    for (const Reference &ref : kReferences) {
        SCOPED_TRACE(std::string(matrixName(ref.colorimetry.matrix)) + " " + rangeName(ref.colorimetry.range) + " " +
                     std::to_string(ref.rgb[0]) + "," + std::to_string(ref.rgb[1]) + "," + std::to_string(ref.rgb[2]));
        FrameBuffer frame = test::makeFrame("YUYV", 2, 1);
        ASSERT_TRUE(fillFrame(frame.view(), ref.colorimetry, ref.rgb[0], ref.rgb[1], ref.rgb[2]));
        const uint8_t *yuyv = frame.data();
        EXPECT_EQ(yuyv[0], ref.ycbcr[0]);
        EXPECT_EQ(yuyv[2], ref.ycbcr[0]);
        EXPECT_EQ(yuyv[1], ref.ycbcr[1]);
        EXPECT_EQ(yuyv[3], ref.ycbcr[2]);
    }
}

TEST(Resample, DownAveragesUpRepeats)
{
    YcbcrImage full = YcbcrImage::allocate(4, 2, 1, 1, true);
    full.cb = {10, 20, 30, 41, 50, 60, 70, 80};
    full.cr = full.cb;
    const YcbcrImage half = resampleChroma(full, 2, 2);
    EXPECT_EQ(half.cb, (std::vector<uint8_t>{35, 55})); // (10+20+50+60)/4, (30+41+70+80)/4 = 55.25
    const YcbcrImage back = resampleChroma(half, 1, 1);
    EXPECT_EQ(back.cr, (std::vector<uint8_t>{35, 35, 55, 55, 35, 35, 55, 55}));
}

} // namespace
} // namespace overlayd
