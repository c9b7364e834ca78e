// SPDX-License-Identifier: Apache-2.0
// The checkerboard-scene alignment check. The synthetic source ray-traces the ground's 1 m checkers through the
// configured (distorting) camera pixel by pixel; the overlay projects a 1 m grid through the same camera with
// clipping, curve subdivision and rasterization. Neither trusts the other: the grid's pixels (the difference between
// the frame with and without the overlay) must lie on the checker edges found in the plain frame by OpenCV's
// Sobel filter. A grid shifted by half a square, the negative control, must fail the same measure.
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

constexpr int kWidth = 640, kHeight = 480;

cv::Mat renderGrey(const std::string &config, const std::string &dir)
{
    cv::Mat bgr = renderFrameBgr(dataPath(config), "GREY", kWidth, kHeight, scratchDir(dir));
    cv::Mat grey;
    if (!bgr.empty())
        cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    return grey;
}

// Checker edges of the plain scene, widened by 2 px (line width and anti-aliasing).
cv::Mat edgeMask(const cv::Mat &plain)
{
    cv::Mat dx, dy, magnitude;
    cv::Sobel(plain, dx, CV_32F, 1, 0);
    cv::Sobel(plain, dy, CV_32F, 0, 1);
    cv::magnitude(dx, dy, magnitude);
    cv::Mat edges = magnitude > 100.0;
    cv::dilate(edges, edges, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
    return edges;
}

// The share of overlay pixels (changed by > 40 levels) lying on checker edges, in the near ground (the lower half
// of the frame, where squares are tens of pixels wide and edges are unambiguous).
double shareOnEdges(const cv::Mat &withGrid, const cv::Mat &plain, int *overlayPixels)
{
    cv::Mat difference;
    cv::absdiff(withGrid, plain, difference);
    const cv::Rect near(0, kHeight / 2, kWidth, kHeight / 2);
    const cv::Mat overlay = difference(near) > 40;
    const cv::Mat onEdges = overlay & edgeMask(plain)(near);
    *overlayPixels = cv::countNonZero(overlay);
    return *overlayPixels ? double(cv::countNonZero(onEdges)) / *overlayPixels : 0.0;
}

TEST(Alignment, GridLiesOnTheCheckerEdges)
{
    const cv::Mat plain = renderGrey("alignment_plain.toml", "plain");
    const cv::Mat grid = renderGrey("alignment_grid.toml", "grid");
    ASSERT_FALSE(plain.empty());
    ASSERT_FALSE(grid.empty());
    int overlayPixels = 0;
    const double share = shareOnEdges(grid, plain, &overlayPixels);
    EXPECT_GT(overlayPixels, 2000); // the grid was drawn at all
    std::printf("grid: %d overlay pixels, %.4f on checker edges\n", overlayPixels, share);
    EXPECT_GE(share, 0.95) << overlayPixels << " overlay pixels";
}

TEST(Alignment, ShiftedGridIsCaughtByTheSameMeasure)
{
    const cv::Mat plain = renderGrey("alignment_plain.toml", "plain-control");
    const cv::Mat shifted = renderGrey("alignment_shifted.toml", "shifted");
    ASSERT_FALSE(plain.empty());
    ASSERT_FALSE(shifted.empty());
    int overlayPixels = 0;
    const double share = shareOnEdges(shifted, plain, &overlayPixels);
    EXPECT_GT(overlayPixels, 2000);
    std::printf("shifted grid: %d overlay pixels, %.4f on checker edges\n", overlayPixels, share);
    EXPECT_LT(share, 0.5);
}

} // namespace
} // namespace overlayd::test
