// SPDX-License-Identifier: Apache-2.0
// Text placement and readability through the real binary. Alignment: `text` and `label` annotations with `align`
// left, centre and right at the same x, rendered in RGB24 over a plain white frame; each box is found in the pixels
// and must start, be centred on, or end at that column, all three the same width. Axis labels: the blue "Z" over a
// black ground must contrast with what is around it (WCAG's ratio of relative luminances).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <opencv2/core.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

constexpr int kWidth = 640, kHeight = 360;
constexpr int kColumn = 320; // every box is placed by this column
// The plate's padding past the text's box on each side (docs/config.md): 15% of the size, at least 2 px.
constexpr int kPadding24 = 4, kPadding20 = 3;

const std::string kScene = "[source]\nkind = \"synthetic\"\nformat = \"RGB24\"\nwidth = 640\nheight = 360\n"
                           "fps = 30.0\n[source.synthetic]\npattern = \"checkerboard\"\nchecker_px = 16384\n"
                           "[camera]\neye = [0.0, -6.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\n";

std::string screenText(int row, const std::string &align)
{
    return "[[annotation]]\ntype = \"text\"\ntext = \"Align me\"\nposition = [" + std::to_string(kColumn) + ".0, " +
           std::to_string(row) + ".0]\nsize_px = 24.0\nbackground = \"#ff00ff\"\n" +
           (align.empty() ? "" : "align = \"" + align + "\"\n") + "style = { colour = \"#00a000\" }\n";
}

// A label on the world origin, moved down by `down` px so that the boxes do not overlap.
std::string label(int down, const std::string &align)
{
    return "[[annotation]]\ntype = \"label\"\nanchor = [0.0, 0.0, 0.0]\ntext = \"Label\"\noffset_px = [0.0, " +
           std::to_string(down) + ".0]\nsize_px = 20.0\nbackground = \"#ff00ff\"\nalign = \"" + align +
           "\"\nstyle = { colour = \"#00a000\" }\n";
}

// The first and last column of non-white pixels in rows [top, bottom) (the plate); `greenOnly`: of the letters'
// green ink.
std::pair<int, int> inkColumns(const cv::Mat &bgr, int top, int bottom, bool greenOnly = false)
{
    int first = kWidth, last = -1;
    for (int y = top; y < bottom; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
            const bool ink = greenOnly ? p[1] > p[0] + 60 && p[1] > p[2] + 60 : p[0] + p[1] + p[2] < 3 * 255 - 60;
            if (ink) {
                first = std::min(first, x);
                last = std::max(last, x);
            }
        }
    return {first, last};
}

// A world point's pixel by `overlayd project --json` (NaN when it gave none).
std::pair<double, double> projectedPixel(const std::string &config, const std::string &point, const std::string &dir)
{
    const RunResult run = runOverlayd("project --config " + config + " --json -- " + point, dir);
    EXPECT_EQ(run.exitStatus, 0) << run.all();
    const size_t at = run.out.find("\"pixel\"");
    double u = std::nan(""), v = std::nan("");
    if (at == std::string::npos || std::sscanf(run.out.c_str() + run.out.find('[', at), "[%lf ,%lf", &u, &v) != 2)
        ADD_FAILURE() << "no pixel in: " << run.out;
    return {u, v};
}

TEST(TextAlign, TextBoxesStartAtCentreOnAndEndAtTheirPosition)
{
    const std::string dir = scratchDir("text_align");
    writeFile(dir + "/align.toml", kScene + screenText(20, "") + screenText(80, "left") + screenText(140, "centre") +
                                       screenText(200, "right"));
    const cv::Mat frame = renderFrameBgr("align.toml", "RGB24", kWidth, kHeight, dir);
    ASSERT_FALSE(frame.empty());
    const auto unset = inkColumns(frame, 20, 60), left = inkColumns(frame, 80, 120),
               centre = inkColumns(frame, 140, 180), right = inkColumns(frame, 200, 240);
    EXPECT_EQ(unset, left) << "left is the default";
    // The text's box starts or ends on the column; its plate reaches the padding further.
    EXPECT_EQ(left.first, kColumn - kPadding24);
    EXPECT_EQ(right.second, kColumn + kPadding24);
    const int width = left.second - left.first;
    EXPECT_GT(width, 50);
    EXPECT_EQ(centre.second - centre.first, width);
    EXPECT_EQ(right.second - right.first, width);
    // The middle column (the left one of two) on the position.
    EXPECT_EQ(centre.first + width / 2, kColumn) << centre.first << ".." << centre.second;
}

TEST(TextAlign, LabelsAlignOnTheirAnchor)
{
    const std::string dir = scratchDir("label_align");
    writeFile(dir + "/labels.toml", kScene + label(-70, "left") + label(-35, "right"));
    const cv::Mat frame = renderFrameBgr("labels.toml", "RGB24", kWidth, kHeight, dir);
    ASSERT_FALSE(frame.empty());
    // The origin's pixel: the column both labels are placed by.
    const auto [u, v] = projectedPixel("labels.toml", "0 0 0", dir);
    const int column = int(std::lround(u)), row = int(std::lround(v));
    ASSERT_GT(row, 80);
    const auto left = inkColumns(frame, row - 70, row - 45), right = inkColumns(frame, row - 35, row - 10);
    EXPECT_EQ(left.first, column - kPadding20);
    EXPECT_EQ(right.second, column + kPadding20);
    EXPECT_EQ(left.second - left.first, right.second - right.first);
}

// The letters keep clear of their plate's edges: at least the padding between the ink and either end of the plate.
TEST(TextPlate, LettersDoNotTouchItsEdges)
{
    const std::string dir = scratchDir("text_plate");
    writeFile(dir + "/plate.toml", kScene + screenText(80, "left"));
    const cv::Mat frame = renderFrameBgr("plate.toml", "RGB24", kWidth, kHeight, dir);
    ASSERT_FALSE(frame.empty());
    const auto plate = inkColumns(frame, 80, 120), letters = inkColumns(frame, 80, 120, true);
    ASSERT_GE(letters.second, 0);
    EXPECT_GE(letters.first - plate.first, kPadding24)
        << "plate " << plate.first << ".." << plate.second << ", ink " << letters.first << ".." << letters.second;
    EXPECT_GE(plate.second - letters.second, kPadding24)
        << "plate " << plate.first << ".." << plate.second << ", ink " << letters.first << ".." << letters.second;
}

// WCAG 2's relative luminance of an 8-bit sRGB pixel (BGR).
double luminance(const cv::Vec3b &bgr)
{
    const auto linear = [](uint8_t c) {
        const double v = c / 255.0;
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    return 0.2126 * linear(bgr[2]) + 0.7152 * linear(bgr[1]) + 0.0722 * linear(bgr[0]);
}

TEST(AxisLabels, ContrastWithABlackGround)
{
    const std::string dir = scratchDir("axis_labels");
    writeFile(dir + "/axes.toml", kScene +
                                      "[[annotation]]\ntype = \"rect\"\nposition = [0.0, 0.0]\nsize = [640.0, 360.0]\n"
                                      "filled = true\nstyle = { colour = \"black\" }\n"
                                      "[[annotation]]\ntype = \"axes\"\nlength = 1.0\nlabels = true\n");
    const cv::Mat frame = renderFrameBgr("axes.toml", "RGB24", kWidth, kHeight, dir);
    ASSERT_FALSE(frame.empty());
    const auto [u, v] = projectedPixel("axes.toml", "0 0 1", dir);
    // The "Z" sits 4 px right of and below its tip; its box is at least 16 px tall. Its ink is the bluest pixel
    // there, the ground around the ink the most common colour of the box.
    const int x0 = int(std::lround(u)) + 5, y0 = int(std::lround(v)) + 5;
    ASSERT_TRUE(x0 >= 0 && y0 >= 0 && x0 + 10 < kWidth && y0 + 14 < kHeight);
    cv::Vec3b ink{}, around{};
    int bluest = -1000;
    std::map<std::array<uint8_t, 3>, int> counts;
    for (int y = y0; y < y0 + 14; ++y)
        for (int x = x0; x < x0 + 10; ++x) {
            const cv::Vec3b p = frame.at<cv::Vec3b>(y, x);
            if (p[0] - std::max(p[1], p[2]) > bluest) {
                bluest = p[0] - std::max(p[1], p[2]);
                ink = p;
            }
            ++counts[{p[0], p[1], p[2]}];
        }
    const auto mode = std::max_element(counts.begin(), counts.end(),
                                       [](const auto &a, const auto &b) { return a.second < b.second; });
    around = cv::Vec3b(mode->first[0], mode->first[1], mode->first[2]);
    const double a = luminance(ink), b = luminance(around);
    const double ratio = (std::max(a, b) + 0.05) / (std::min(a, b) + 0.05);
    EXPECT_GE(ratio, 4.5) << "the Z label's ink " << ink << " on " << around << ": contrast " << ratio;
}

} // namespace
} // namespace overlayd::test
