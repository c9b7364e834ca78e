// SPDX-License-Identifier: Apache-2.0
// JpegEncoder: every format of the table, in every colorimetry, encodes to a JPEG of the frame's size and chroma
// subsampling that OpenCV's decoder (JFIF: full-range BT.601) turns back into the RGB of our own frameToRgb, within
// JPEG's loss; a wrong colorimetry is far outside that tolerance, which shows the comparison can fail.
#include "media/jpeg/jpeg_encoder.h"

#include <cctype>
#include <ostream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <turbojpeg.h>

#include "jpeg_test_frames.h"

namespace overlayd {
namespace {

using test::meanError;
using test::patternFrame;
using test::worstChannel;

constexpr int kQuality = 95;
// Mean absolute error per channel, in code values: quality 95 plus, at the bars' edges, the decoder's smooth
// chroma upsampling against frameToRgb's nearest-neighbour chroma. Measured: at most 2.44 (B, 4:2:0, BT.709);
// RGB24 through libjpeg-turbo's own RGB conversion gives 2.16 on the same pattern.
constexpr double kTolerance = 3.0;
// Largest difference at the bars' centres, where the colour is flat: measured 1 at most.
constexpr int kBarTolerance = 2;

constexpr Colorimetry kBt601Limited{YcbcrMatrix::Bt601, ColourRange::Limited};
constexpr Colorimetry kBt601Full{YcbcrMatrix::Bt601, ColourRange::Full};
constexpr Colorimetry kBt709Limited{YcbcrMatrix::Bt709, ColourRange::Limited};
constexpr Colorimetry kBt709Full{YcbcrMatrix::Bt709, ColourRange::Full};

// Written out by name rather than derived from the table, so that the test does not share the encoder's logic; a
// format added to the table fails here until it is added.
int expectedSubsampling(const std::string &name)
{
    static const std::set<std::string> k422{"YUYV", "UYVY", "YVYU", "NV16"};
    static const std::set<std::string> k420{"NV12", "NV21", "YUV420", "YVU420"};
    static const std::set<std::string> kRgb{"RGB24",  "BGR24",  "XRGB32", "XBGR32", "RGBX32",
                                            "BGRX32", "ARGB32", "ABGR32", "RGBA32", "BGRA32"};
    if (k422.count(name))
        return TJSAMP_422;
    if (k420.count(name) || kRgb.count(name))
        return TJSAMP_420;
    return name == "GREY" ? TJSAMP_GRAY : -1;
}

struct Case {
    std::string format;
    Colorimetry colorimetry;
};

void PrintTo(const Case &c, std::ostream *os)
{
    *os << c.format << " " << matrixName(c.colorimetry.matrix) << " " << rangeName(c.colorimetry.range);
}

std::vector<Case> everyFormatAndColorimetry()
{
    std::vector<Case> cases;
    for (const PixelFormatInfo &format : pixelFormats())
        for (Colorimetry c : {kBt601Limited, kBt601Full, kBt709Limited, kBt709Full})
            cases.push_back({std::string(format.name), c});
    return cases;
}

// gtest names allow only letters, digits and '_': "YUYV_BT601_limited".
std::string caseName(const testing::TestParamInfo<Case> &info)
{
    std::string name = info.param.format + "_" + matrixName(info.param.colorimetry.matrix) + "_" +
                       rangeName(info.param.colorimetry.range);
    std::erase_if(name, [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '_'; });
    return name;
}

class EveryFormat : public testing::TestWithParam<Case>
{
protected:
    void check(unsigned width, unsigned height, unsigned stridePadding)
    {
        const Case &c = GetParam();
        FrameBuffer frame = patternFrame(c.format, width, height, c.colorimetry, stridePadding);
        auto encoder = JpegEncoder::create();
        ASSERT_TRUE(encoder) << encoder.error().message;
        std::vector<uint8_t> jpeg;
        auto encoded = encoder->encode(frame.view(), c.colorimetry, kQuality, jpeg);
        ASSERT_TRUE(encoded) << encoded.error().message;

        const test::JpegHeader header = test::readHeader(jpeg);
        EXPECT_EQ(header.width, int(width));
        EXPECT_EQ(header.height, int(height));
        EXPECT_EQ(header.subsampling, expectedSubsampling(c.format));
        const auto error = meanError(jpeg, frame.view(), c.colorimetry);
        EXPECT_LT(worstChannel(error), kTolerance)
            << "mean |JPEG - frameToRgb| R " << error[0] << " G " << error[1] << " B " << error[2];
        EXPECT_LE(test::worstBarError(jpeg, frame.view(), c.colorimetry), kBarTolerance);
    }
};

TEST_P(EveryFormat, DecodesToTheFramesColours)
{
    check(320, 240, 0);
}

// Odd sizes (partial macropixels and MCUs) and padded rows, which the planar formats hand to libjpeg-turbo as they are.
TEST_P(EveryFormat, OddSizeAndPaddedStride)
{
    check(327, 245, 24);
}

INSTANTIATE_TEST_SUITE_P(JpegEncoder, EveryFormat, testing::ValuesIn(everyFormatAndColorimetry()), caseName);

struct WrongClaim {
    Colorimetry actual, claimed;
};

// The same comparison must fail when the encoder is told the wrong colorimetry: a wrong range or a wrong matrix moves
// the saturated bars by tens of code values.
TEST(JpegEncoder, WrongColorimetryIsFarOutsideTheTolerance)
{
    const WrongClaim claims[] = {{kBt601Limited, kBt601Full},
                                 {kBt601Full, kBt601Limited},
                                 {kBt709Limited, kBt601Limited},
                                 {kBt601Limited, kBt709Limited}};
    auto encoder = JpegEncoder::create();
    ASSERT_TRUE(encoder);
    for (const char *format : {"YUYV", "NV12", "YUV420"}) {
        for (const WrongClaim &claim : claims) {
            FrameBuffer frame = patternFrame(format, 320, 240, claim.actual);
            std::vector<uint8_t> jpeg;
            ASSERT_TRUE(encoder->encode(frame.view(), claim.claimed, kQuality, jpeg));
            const auto error = meanError(jpeg, frame.view(), claim.actual);
            EXPECT_GT(worstChannel(error), 2.0 * kTolerance)
                << format << " " << matrixName(claim.actual.matrix) << " " << rangeName(claim.actual.range)
                << " encoded as " << matrixName(claim.claimed.matrix) << " " << rangeName(claim.claimed.range);
        }
    }
}

TEST(JpegEncoder, FullRangeBt601PlanarFramesAreCompressedInPlace)
{
    FrameBuffer frame = patternFrame("YUV420", 64, 48, kBt601Full, 8);
    auto encoder = JpegEncoder::create();
    ASSERT_TRUE(encoder);
    std::vector<uint8_t> jpeg;
    ASSERT_TRUE(encoder->encode(frame.view(), kBt601Full, kQuality, jpeg));
    const FrameView view = frame.view();
    for (unsigned p = 0; p < 3; ++p) {
        EXPECT_EQ(encoder->planes().data()[p], view.planes[p].data) << "plane " << p;
        EXPECT_EQ(encoder->planes().strides()[p], int(view.planes[p].stride)) << "plane " << p;
    }
}

TEST(JpegEncoder, RefusesBadQualityAndBadFrames)
{
    auto encoder = JpegEncoder::create();
    ASSERT_TRUE(encoder);
    FrameBuffer frame = patternFrame("NV12", 32, 32, kBt601Limited);
    std::vector<uint8_t> jpeg;
    for (int quality : {0, 101}) {
        auto encoded = encoder->encode(frame.view(), kBt601Limited, quality, jpeg);
        ASSERT_FALSE(encoded);
        EXPECT_EQ(encoded.error().code, ErrorCode::InvalidArgument);
    }
    FrameView truncated = frame.view();
    truncated.planes[1].size /= 2;
    auto encoded = encoder->encode(truncated, kBt601Limited, kQuality, jpeg);
    ASSERT_FALSE(encoded);
    EXPECT_EQ(encoded.error().code, ErrorCode::InvalidArgument);
    EXPECT_FALSE(encoder->encode(FrameView{}, kBt601Limited, kQuality, jpeg));
}

} // namespace
} // namespace overlayd
