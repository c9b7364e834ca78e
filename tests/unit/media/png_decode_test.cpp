// SPDX-License-Identifier: Apache-2.0
// media/codec's PNG decoding against OpenCV's imgcodecs on files libpng writes here: every colour type and bit
// depth, with and without tRNS, interlaced too. Rgba must equal what config/ made of cv::imread(IMREAD_UNCHANGED)
// (16 bits times 1/257, then RGBA), Rgb what cv::imread(IMREAD_COLOR) gives (which keeps the high byte of 16 bits:
// at most 1 apart there).
#include <png.h>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "image_test_files.h"

using namespace overlayd;
using namespace overlayd::test;

namespace {

struct PngCase {
    const char *name;
    int colourType, bitDepth;
    bool transparency = false, interlaced = false;
};

const PngCase kCases[] = {
    {"grey1", PNG_COLOR_TYPE_GRAY, 1},
    {"grey2", PNG_COLOR_TYPE_GRAY, 2},
    {"grey4", PNG_COLOR_TYPE_GRAY, 4},
    {"grey8", PNG_COLOR_TYPE_GRAY, 8},
    {"grey16", PNG_COLOR_TYPE_GRAY, 16},
    {"grey2_trns", PNG_COLOR_TYPE_GRAY, 2, true},
    {"grey8_trns", PNG_COLOR_TYPE_GRAY, 8, true},
    {"grey16_trns", PNG_COLOR_TYPE_GRAY, 16, true},
    {"grey_alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8},
    {"grey_alpha16", PNG_COLOR_TYPE_GRAY_ALPHA, 16},
    {"rgb8", PNG_COLOR_TYPE_RGB, 8},
    {"rgb16", PNG_COLOR_TYPE_RGB, 16},
    {"rgb8_trns", PNG_COLOR_TYPE_RGB, 8, true},
    {"rgb16_trns", PNG_COLOR_TYPE_RGB, 16, true},
    {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8},
    {"rgba16", PNG_COLOR_TYPE_RGB_ALPHA, 16},
    {"palette1", PNG_COLOR_TYPE_PALETTE, 1},
    {"palette2", PNG_COLOR_TYPE_PALETTE, 2},
    {"palette4", PNG_COLOR_TYPE_PALETTE, 4},
    {"palette8", PNG_COLOR_TYPE_PALETTE, 8},
    {"palette4_trns", PNG_COLOR_TYPE_PALETTE, 4, true},
    {"palette8_trns", PNG_COLOR_TYPE_PALETTE, 8, true},
    {"grey4_interlaced", PNG_COLOR_TYPE_GRAY, 4, false, true},
    {"rgba8_interlaced", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, true},
    {"palette8_trns_interlaced", PNG_COLOR_TYPE_PALETTE, 8, true, true},
};

class PngDecode : public ::testing::TestWithParam<PngCase>
{
protected:
    void SetUp() override
    {
        const PngCase &c = GetParam();
        // 13 x 7: rows that end inside a byte at 1, 2 and 4 bits, and partial Adam7 blocks.
        picture_ = randomPicture(13, 7, c.colourType, c.bitDepth, c.transparency, unsigned(c.bitDepth * 31 + 7));
        picture_.interlaced = c.interlaced;
        path_ = folder_.path(std::string(c.name) + ".png");
        ASSERT_TRUE(writePng(path_, picture_)) << path_;
        file_ = readFile(path_);
    }

    TestFolder folder_;
    PngPicture picture_;
    std::string path_;
    std::vector<uint8_t> file_;
};

std::string caseName(const ::testing::TestParamInfo<PngCase> &info)
{
    return info.param.name;
}

} // namespace

TEST_P(PngDecode, RgbaIsWhatConfigMadeOfOpenCvsUnchangedRead)
{
    const auto decoded = decodeImage(file_, ImageChannels::Rgba, 4096);
    ASSERT_TRUE(decoded) << decoded.error().message;
    EXPECT_EQ(decoded->width, 13u);
    EXPECT_EQ(decoded->height, 7u);
    const cv::Mat ours = asMat(*decoded), reference = openCvRgba(path_);
    ASSERT_FALSE(reference.empty());
    const bool greyKey = GetParam().colourType == PNG_COLOR_TYPE_GRAY && GetParam().transparency;
    if (!greyKey) {
        EXPECT_EQ(maxDifference(ours, reference), 0);
        return;
    }
    // OpenCV drops a grey image's tRNS; here it is alpha, as the PNG specification means it: colours as OpenCV's,
    // alpha 0 exactly where the sample is the transparent grey.
    cv::Mat oursColour, referenceColour;
    cv::cvtColor(ours, oursColour, cv::COLOR_RGBA2RGB);
    cv::cvtColor(reference, referenceColour, cv::COLOR_RGBA2RGB);
    EXPECT_EQ(maxDifference(oursColour, referenceColour), 0);
    unsigned transparent = 0;
    for (size_t i = 0; i < picture_.samples.size(); ++i) {
        const bool key = picture_.samples[i] == picture_.transparentColour[0];
        transparent += key;
        EXPECT_EQ(decoded->pixels[i * 4 + 3], key ? 0 : 255) << "pixel " << i;
    }
    EXPECT_GE(transparent, 13u * 7u / 3u);
}

TEST_P(PngDecode, RgbIsOpenCvsColourReadAndRgbaWithoutAlpha)
{
    const auto rgb = decodeImage(file_, ImageChannels::Rgb, 4096);
    const auto rgba = decodeImage(file_, ImageChannels::Rgba, 4096);
    ASSERT_TRUE(rgb) << rgb.error().message;
    ASSERT_TRUE(rgba) << rgba.error().message;
    cv::Mat withoutAlpha;
    cv::cvtColor(asMat(*rgba), withoutAlpha, cv::COLOR_RGBA2RGB);
    EXPECT_EQ(maxDifference(asMat(*rgb), withoutAlpha), 0);
    const cv::Mat reference = openCvRgb(path_);
    ASSERT_FALSE(reference.empty());
    const int difference = maxDifference(asMat(*rgb), reference);
    EXPECT_GE(difference, 0);
    EXPECT_LE(difference, GetParam().bitDepth == 16 ? 1 : 0);
}

TEST_P(PngDecode, TheHeaderGivesTheSize)
{
    const auto info = readImageInfo(file_);
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_EQ(info->type, ImageFileType::Png);
    EXPECT_EQ(info->width, 13u);
    EXPECT_EQ(info->height, 7u);
}

INSTANTIATE_TEST_SUITE_P(EveryColourTypeAndDepth, PngDecode, ::testing::ValuesIn(kCases), caseName);
