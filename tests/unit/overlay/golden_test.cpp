// SPDX-License-Identifier: Apache-2.0
// Golden frames: the demo scene blended on mid-grey at 320x240, per format and viewport origin, read back through
// OpenCV's converters (test::toBgr) and compared with PNGs in tests/data/overlay/.
//
// Tolerance: every channel within kChannelTolerance codes of the golden, except at most kOutlierFraction of the
// pixels (anti-aliasing and glyph rasterization may shift by a code or so across compilers and FreeType versions).
// Regenerate after an intended change with: OVERLAYD_UPDATE_GOLDENS=1 build-*/tests/unit/overlay/overlay_tests
// --gtest_filter='Golden*' (then look at the PNGs before committing them).
#include <chrono>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "scene_fixture.h"

namespace overlayd {
namespace {

constexpr int kChannelTolerance = 3;
constexpr double kOutlierFraction = 0.005;
constexpr unsigned kWidth = 320, kHeight = 240;

struct GoldenCase {
    std::string format;
    Origin origin;
};

void PrintTo(const GoldenCase &c, std::ostream *os)
{
    *os << c.format << (c.origin == Origin::TopLeft ? " top-left" : " bottom-left");
}

std::string caseName(const testing::TestParamInfo<GoldenCase> &info)
{
    return info.param.format + (info.param.origin == Origin::TopLeft ? "_top_left" : "_bottom_left");
}

std::vector<GoldenCase> cases()
{
    std::vector<GoldenCase> out;
    for (const PixelFormatInfo &info : pixelFormats())
        out.push_back({std::string(info.name), Origin::TopLeft});
    for (const char *name : {"YUYV", "NV12", "YUV420", "RGB24", "GREY"})
        out.push_back({name, Origin::BottomLeft});
    return out;
}

cv::Mat renderDemo(const GoldenCase &c)
{
    test::TestFrame frame = test::makeFrame(c.format, kWidth, kHeight, 8);
    test::fillRgb(frame, Colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited}, 128, 128, 128);
    auto renderer = test::makeRenderer(test::demoScene(true), test::groundCamera(kWidth, kHeight, c.origin),
                                       test::streamFormat(c.format, kWidth, kHeight));
    FrameMetadata metadata;
    metadata.sequence = 42;
    const Status status = renderer->blend(frame.view(), metadata, 30.0);
    EXPECT_TRUE(status.ok());
    EXPECT_TRUE(frame.guardIntact());
    return test::toBgr(frame);
}

class Golden : public testing::TestWithParam<GoldenCase>
{};

TEST_P(Golden, MatchesStoredFrame)
{
    const GoldenCase &c = GetParam();
    const cv::Mat bgr = renderDemo(c);
    const std::string path = std::string(OVERLAYD_TEST_DATA_DIR) + "/" + caseName({c, 0}) + ".png";
    if (std::getenv("OVERLAYD_UPDATE_GOLDENS")) {
        ASSERT_TRUE(cv::imwrite(path, bgr, {cv::IMWRITE_PNG_COMPRESSION, 9})) << path;
        GTEST_SKIP() << "wrote " << path;
    }
    const cv::Mat golden = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_FALSE(golden.empty()) << "missing golden " << path << " (see the comment at the top of this file)";
    ASSERT_EQ(golden.size(), bgr.size());
    cv::Mat diff, worst;
    cv::absdiff(bgr, golden, diff);
    std::vector<cv::Mat> channels;
    cv::split(diff, channels);
    worst = cv::max(cv::max(channels[0], channels[1]), channels[2]);
    const int outliers = cv::countNonZero(worst > kChannelTolerance);
    EXPECT_LE(outliers, kOutlierFraction * kWidth * kHeight) << "pixels off by more than " << kChannelTolerance;
    // The overlay is really there: a good part of the frame differs from the mid-grey it started as.
    cv::Mat grey(bgr.size(), CV_8UC3, cv::Scalar::all(128)), changed;
    cv::absdiff(bgr, grey, changed);
    cv::split(changed, channels);
    EXPECT_GT(cv::countNonZero(cv::max(cv::max(channels[0], channels[1]), channels[2]) > 8), 2000);
}

INSTANTIATE_TEST_SUITE_P(Formats, Golden, testing::ValuesIn(cases()), caseName);

} // namespace
} // namespace overlayd
