// SPDX-License-Identifier: Apache-2.0
// Image annotations through the real binary: config/examples/images.toml (with an asymmetric picture in place of its
// logo) rendered in RGB24, against a render of the same scene without its images and an independent composition made
// here with OpenCV (the picture blended by the "over" rule in doubles; the ground sign warped by cv::warpPerspective
// onto the corners `overlayd project` gives for the sign's world corners).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

#include "harness.h"

namespace overlayd::test {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

std::string exampleText()
{
    const std::vector<uint8_t> bytes = readFile(std::string(OVERLAYD_SOURCE_DIR) + "/config/examples/images.toml");
    return std::string(bytes.begin(), bytes.end());
}

// The example in RGB24 (exact colours to compare with), without its snapshot sink (render writes one file).
std::string rgbExample()
{
    std::string text = exampleText();
    const size_t format = text.find("format = \"YUYV\"");
    EXPECT_NE(format, std::string::npos);
    text.replace(format, 15, "format = \"RGB24\"");
    return text.substr(0, text.find("[[sink]]"));
}

// The picture the test puts in place of the example's logo (a symmetric frame, which would hide a mirrored or
// upside-down image): smooth gradients in every channel, alpha included, and a solid block in its top-left corner.
cv::Mat asymmetricLogo()
{
    cv::Mat logo(48, 160, CV_8UC4);
    for (int y = 0; y < logo.rows; ++y)
        for (int x = 0; x < logo.cols; ++x) {
            const bool corner = x < 40 && y < 16;
            logo.at<cv::Vec4b>(y, x) =
                corner ? cv::Vec4b(20, 230, 250, 255)
                       : cv::Vec4b(static_cast<uint8_t>(x * 255 / 159), static_cast<uint8_t>(y * 255 / 47), 90,
                                   static_cast<uint8_t>(100 + x * 155 / 159));
        }
    return logo;
}

// The same scene with its image annotations left out: the background the images are blended over.
std::string withoutImages(const std::string &text)
{
    const size_t firstImage = text.find("# On the screen");
    EXPECT_NE(firstImage, std::string::npos);
    return text.substr(0, firstImage);
}

struct Renders {
    cv::Mat withImages, background; // BGR
};

Renders renderBoth(const std::string &dir)
{
    EXPECT_TRUE(cv::imwrite(dir + "/logo.png", asymmetricLogo()));
    writeFile(dir + "/images.toml", rgbExample());
    writeFile(dir + "/background.toml", withoutImages(rgbExample()));
    Renders r;
    r.withImages = renderFrameBgr("images.toml", "RGB24", kWidth, kHeight, dir);
    std::filesystem::create_directories(dir + "/bg");
    r.background = renderFrameBgr("../background.toml", "RGB24", kWidth, kHeight, dir + "/bg");
    return r;
}

// The logo as straight-alpha BGRA doubles in [0, 1].
cv::Mat logoBgra()
{
    cv::Mat f;
    asymmetricLogo().convertTo(f, CV_64FC4, 1.0 / 255.0);
    return f;
}

// "over" of a straight-alpha BGRA picture (already in frame coordinates) on a BGR background, scaled by opacity.
cv::Mat composite(const cv::Mat &background, const cv::Mat &bgraOnFrame, double opacity)
{
    cv::Mat out(background.size(), CV_8UC3);
    for (int y = 0; y < background.rows; ++y)
        for (int x = 0; x < background.cols; ++x) {
            const cv::Vec4d p = bgraOnFrame.at<cv::Vec4d>(y, x);
            const double a = p[3] * opacity;
            for (int c = 0; c < 3; ++c) {
                const double bg = background.at<cv::Vec3b>(y, x)[c];
                out.at<cv::Vec3b>(y, x)[c] = cv::saturate_cast<uint8_t>(bg * (1 - a) + p[c] * 255.0 * a);
            }
        }
    return out;
}

TEST(ImageAnnotation, TheScreenLogoIsBlendedAtItsPositionAtItsOwnSize)
{
    const std::string dir = scratchDir("image_screen_logo");
    const Renders r = renderBoth(dir);
    ASSERT_FALSE(r.withImages.empty());
    ASSERT_FALSE(r.background.empty());

    const cv::Mat logo = logoBgra();
    // position = [16, 16] under the top-left origin: the logo's top-left pixel is (16, 16), one frame pixel per
    // logo pixel.
    cv::Mat onFrame(r.background.size(), CV_64FC4, cv::Scalar::all(0));
    logo.copyTo(onFrame(cv::Rect(16, 16, logo.cols, logo.rows)));
    const cv::Mat expected = composite(r.background, onFrame, 1.0);

    const cv::Rect box(16, 16, logo.cols, logo.rows);
    cv::Mat diff;
    cv::absdiff(r.withImages(box), expected(box), diff);
    double worst = 0;
    cv::minMaxLoc(diff.reshape(1), nullptr, &worst);
    EXPECT_LE(worst, 2.0) << "the logo's pixels differ from an independent over-blend by up to " << worst;
    // It is really there: the logo changes its box (its alpha is not zero everywhere).
    cv::Mat changed;
    cv::absdiff(r.withImages(box), r.background(box), changed);
    EXPECT_GT(cv::countNonZero(changed.reshape(1) > 20), logo.total() / 10);
    // And nothing else on the top rows moved: the pixels right of and below the box are the background's.
    const cv::Rect right(16 + logo.cols + 1, 0, 100, 16 + logo.rows + 1), below(0, 16 + logo.rows + 1, 200, 4);
    EXPECT_EQ(cv::norm(r.withImages(right), r.background(right), cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(r.withImages(below), r.background(below), cv::NORM_INF), 0.0);
}

TEST(ImageAnnotation, TheGroundSignLiesOnTheProjectedCornersOfItsWorldRectangle)
{
    const std::string dir = scratchDir("image_ground_sign");
    const Renders r = renderBoth(dir);
    ASSERT_FALSE(r.withImages.empty());
    ASSERT_FALSE(r.background.empty());

    // anchor [0, 2, 0], 4 m x 1.2 m, rows along +X, top toward +Y: the logo's top-left, top-right, bottom-right,
    // bottom-left corners in the world, projected by the binary's own `project` (proven against OpenCV elsewhere).
    const RunResult run =
        runOverlayd("project --config images.toml --json -- -2 2.6 0  2 2.6 0  2 1.4 0  -2 1.4 0", dir);
    ASSERT_EQ(run.exitStatus, 0) << run.all();
    std::vector<cv::Point2f> corners;
    for (size_t at = run.out.find("\"pixel\":["); at != std::string::npos; at = run.out.find("\"pixel\":[", at + 1)) {
        double u = NAN, v = NAN;
        std::sscanf(run.out.c_str() + at + 9, "%lf,%lf", &u, &v);
        corners.emplace_back(static_cast<float>(u), static_cast<float>(v));
    }
    ASSERT_EQ(corners.size(), 4u) << run.out;

    // An independent warp of the logo onto those corners (outer corners of the picture -> the projected points).
    const cv::Mat logo = logoBgra();
    const std::vector<cv::Point2f> source{
        {-0.5f, -0.5f}, {logo.cols - 0.5f, -0.5f}, {logo.cols - 0.5f, logo.rows - 0.5f}, {-0.5f, logo.rows - 0.5f}};
    cv::Mat premultiplied = logo.clone();
    for (auto it = premultiplied.begin<cv::Vec4d>(); it != premultiplied.end<cv::Vec4d>(); ++it)
        for (int c = 0; c < 3; ++c)
            (*it)[c] *= (*it)[3];
    cv::Mat warped;
    cv::warpPerspective(premultiplied, warped, cv::getPerspectiveTransform(source, corners), r.background.size(),
                        cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    for (auto it = warped.begin<cv::Vec4d>(); it != warped.end<cv::Vec4d>(); ++it)
        for (int c = 0; c < 3; ++c)
            (*it)[c] = (*it)[3] > 1e-9 ? (*it)[c] / (*it)[3] : 0.0;
    const cv::Mat expected = composite(r.background, warped, 0.8);

    // Inside the projected quad (shrunk by 2 px, away from the anti-aliased edge): the same picture, to within
    // interpolation differences on the logo's sharp edges.
    std::vector<cv::Point> quad;
    for (const cv::Point2f &c : corners)
        quad.emplace_back(cvRound(c.x), cvRound(c.y));
    cv::Mat inside(r.background.size(), CV_8U, cv::Scalar(0));
    cv::fillConvexPoly(inside, quad, cv::Scalar(255));
    cv::erode(inside, inside, cv::getStructuringElement(cv::MORPH_RECT, {5, 5}));
    cv::Mat diff;
    cv::absdiff(r.withImages, expected, diff);
    cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
    const double insideCount = cv::countNonZero(inside);
    ASSERT_GT(insideCount, 1000.0) << "the sign covers almost nothing: wrong corners?";
    EXPECT_LT(cv::mean(diff, inside)[0], 3.0);
    EXPECT_LT(cv::countNonZero((diff > 40) & inside), insideCount * 0.02);

    // Outside the quad grown by 3 px, the sign changes nothing (the screen logo's box is left out).
    cv::Mat outside;
    cv::fillConvexPoly(outside = cv::Mat(r.background.size(), CV_8U, cv::Scalar(0)), quad, cv::Scalar(255));
    cv::dilate(outside, outside, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
    outside = ~outside;
    outside(cv::Rect(0, 0, 16 + logo.cols + 2, 16 + logo.rows + 2)).setTo(0);
    cv::Mat changed;
    cv::absdiff(r.withImages, r.background, changed);
    cv::cvtColor(changed, changed, cv::COLOR_BGR2GRAY);
    EXPECT_EQ(cv::countNonZero(changed & outside), 0);
}

} // namespace
} // namespace overlayd::test
