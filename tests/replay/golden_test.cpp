// SPDX-License-Identifier: Apache-2.0
// Golden frames: `overlayd render` over scenes covering each kind of pixel format, both viewport origins,
// perspective and orthographic cameras, with and without lens distortion. The raw output is converted to BGR with
// OpenCV and compared with tests/data/replay/golden/<scene>.png.
//
// Tolerance (anti-aliasing and rounding may differ between compilers and CPUs, the geometry may not): the mean
// absolute difference over all channels is at most 1.5 levels, and at most 0.5% of the pixels differ by more than
// 40 levels in any channel. Regenerate after an intended change with
//   OVERLAYD_UPDATE_GOLDENS=1 ctest -R replay.Golden
// and look at the new PNGs before committing them.
#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <ostream>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

struct Scene {
    const char *name;
    const char *format;
};

// Names the case in test listings (CTest shows it) instead of its bytes.
void PrintTo(const Scene &value, std::ostream *out)
{
    *out << value.name;
}

class Golden : public ::testing::TestWithParam<Scene>
{};

TEST_P(Golden, MatchesTheStoredFrame)
{
    const Scene scene = GetParam();
    const std::string dir = scratchDir(std::string("golden-") + scene.name);
    const cv::Mat frame = renderFrameBgr(dataPath(std::string(scene.name) + ".toml"), scene.format, 320, 240, dir);
    ASSERT_FALSE(frame.empty());
    const std::string golden = dataPath(std::string("golden/") + scene.name + ".png");
    if (const char *update = std::getenv("OVERLAYD_UPDATE_GOLDENS"); update && *update == '1') {
        std::filesystem::create_directories(dataPath("golden"));
        ASSERT_TRUE(cv::imwrite(golden, frame));
        GTEST_SKIP() << "wrote " << golden;
    }
    const cv::Mat expected = cv::imread(golden, cv::IMREAD_COLOR);
    ASSERT_FALSE(expected.empty()) << golden << " is missing; regenerate with OVERLAYD_UPDATE_GOLDENS=1";
    ASSERT_EQ(expected.size(), frame.size());

    cv::Mat difference;
    cv::absdiff(frame, expected, difference);
    const cv::Scalar mean = cv::mean(difference);
    const double meanAll = (mean[0] + mean[1] + mean[2]) / 3.0;
    cv::Mat perPixelMax;
    cv::Mat channels[3];
    cv::split(difference, channels);
    perPixelMax = cv::max(channels[0], cv::max(channels[1], channels[2]));
    const double farOff = double(cv::countNonZero(perPixelMax > 40)) / double(frame.total());
    EXPECT_LE(meanAll, 1.5) << scene.name;
    EXPECT_LE(farOff, 0.005) << scene.name;
    if (meanAll > 1.5 || farOff > 0.005) {
        const std::string actual = dir + "/actual.png";
        cv::imwrite(actual, frame);
        ADD_FAILURE() << "the rendered frame is in " << actual;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, Golden,
    ::testing::Values(Scene{"persp_yuyv_top_left", "YUYV"}, Scene{"persp_nv12_bottom_left", "NV12"},
                      Scene{"persp_bgr24_top_left", "BGR24"}, Scene{"ortho_yuv420_top_left", "YUV420"},
                      Scene{"ortho_uyvy_bottom_left", "UYVY"}, Scene{"distorted_rgb24_top_left", "RGB24"},
                      Scene{"distorted_grey_bottom_left", "GREY"}),
    [](const auto &param) { return std::string(param.param.name); });

// The two origins are conventions for pixel coordinates, not a flip of the picture: the same scene rendered under
// either origin is the same image, except for screen text, which sits at its position from the origin's corner.
TEST(Origins, BottomLeftSceneEqualsTopLeftSceneOutsideTheText)
{
    const cv::Mat top = renderFrameBgr(dataPath("persp_yuyv_top_left.toml"), "YUYV", 320, 240, scratchDir("top"));
    const cv::Mat bottom =
        renderFrameBgr(dataPath("persp_nv12_bottom_left.toml"), "NV12", 320, 240, scratchDir("bottom"));
    ASSERT_FALSE(top.empty());
    ASSERT_FALSE(bottom.empty());
    // Rows 30..209 hold neither origin's "frame N" text (14 px high, 4 px from the top or bottom edge).
    const cv::Rect middle(0, 30, 320, 180);
    cv::Mat difference;
    cv::absdiff(top(middle), bottom(middle), difference);
    cv::Mat grey;
    cv::cvtColor(difference, grey, cv::COLOR_BGR2GRAY);
    // YUYV and NV12 subsample chroma differently: allow chroma bleeding at edges, not displaced geometry.
    EXPECT_LE(double(cv::countNonZero(grey > 40)) / double(grey.total()), 0.01);
}

} // namespace
} // namespace overlayd::test
