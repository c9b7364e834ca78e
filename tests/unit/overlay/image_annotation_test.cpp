// SPDX-License-Identifier: Apache-2.0
// Image annotations: a screen image lands at its position, upright under both viewport origins, and is composited
// "over" with its alpha and opacity; a world image's parts land where GLM projects the matching points of its plane;
// it follows the camera, goes with its layer, and is left out (not mis-drawn) behind the camera. Expected colours are
// worked out here from the over formula, and frames are read back through OpenCV (toBgr).
#include <memory>

#include <glm/ext/matrix_projection.hpp>
#include <gtest/gtest.h>

#include "scene_fixture.h"

namespace overlayd {
namespace {

constexpr unsigned kWidth = 320, kHeight = 240;
const Colorimetry kRgb{YcbcrMatrix::Bt601, ColourRange::Full};

// Premultiplied RGBA pixels from straight rows of {r, g, b, a}.
std::shared_ptr<const ImagePixels> imageOf(unsigned width, unsigned height, const std::vector<Rgba> &straight)
{
    auto image = std::make_shared<ImagePixels>();
    image->width = width, image->height = height;
    for (const Rgba &c : straight)
        for (uint8_t v : {uint8_t((c.r * c.a + 127) / 255), uint8_t((c.g * c.a + 127) / 255),
                          uint8_t((c.b * c.a + 127) / 255), c.a})
            image->rgba.push_back(v);
    return image;
}

// Four quadrants: red, green / white, blue (top row first), each q x q pixels, opaque.
std::shared_ptr<const ImagePixels> quadrants(unsigned q)
{
    std::vector<Rgba> pixels;
    for (unsigned y = 0; y < 2 * q; ++y)
        for (unsigned x = 0; x < 2 * q; ++x)
            pixels.push_back(y < q ? (x < q ? kRed : kGreen) : (x < q ? kWhite : kBlue));
    return imageOf(2 * q, 2 * q, pixels);
}

test::TestFrame greyFrame()
{
    test::TestFrame frame = test::makeFrame("RGB24", kWidth, kHeight, 0);
    test::fillRgb(frame, kRgb, 100, 100, 100);
    return frame;
}

// The frame after one blend of the scene through `camera`, as BGR.
cv::Mat rendered(const OverlayScene &scene, const Camera &camera)
{
    auto renderer = test::makeRenderer(scene, camera, test::streamFormat("RGB24", kWidth, kHeight));
    test::TestFrame frame = greyFrame();
    EXPECT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    return test::toBgr(frame).clone();
}

cv::Vec3b rgb(uint8_t r, uint8_t g, uint8_t b)
{
    return {b, g, r};
}

OverlayScene screenImage(std::shared_ptr<const ImagePixels> image, glm::dvec2 position, double opacity = 1.0)
{
    ImageShape shape;
    shape.image = std::move(image);
    shape.position = position;
    shape.opacity = opacity;
    return {{}, {test::annotation("logo", shape, kWhite, 1.0, "hud")}, std::nullopt};
}

TEST(ImageAnnotation, ScreenImageLandsAtItsPositionUprightUnderBothOrigins)
{
    const auto image = quadrants(2); // 4x4
    const cv::Mat topLeft = rendered(screenImage(image, {10, 20}), test::groundCamera(kWidth, kHeight));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(20, 10), rgb(255, 0, 0));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(20, 13), rgb(0, 255, 0));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(23, 10), rgb(255, 255, 255));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(23, 13), rgb(0, 0, 255));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(20, 9), rgb(100, 100, 100));
    EXPECT_EQ(topLeft.at<cv::Vec3b>(24, 10), rgb(100, 100, 100));

    // Bottom-left: user rows 20..23 count up from the bottom row; the image's top row is the highest of them.
    const cv::Mat bottomLeft =
        rendered(screenImage(image, {10, 20}), test::groundCamera(kWidth, kHeight, Origin::BottomLeft));
    const int top = int(kHeight) - 1 - 23, bottom = int(kHeight) - 1 - 20;
    EXPECT_EQ(bottomLeft.at<cv::Vec3b>(top, 10), rgb(255, 0, 0));
    EXPECT_EQ(bottomLeft.at<cv::Vec3b>(top, 13), rgb(0, 255, 0));
    EXPECT_EQ(bottomLeft.at<cv::Vec3b>(bottom, 10), rgb(255, 255, 255));
    EXPECT_EQ(bottomLeft.at<cv::Vec3b>(bottom, 13), rgb(0, 0, 255));
    EXPECT_EQ(bottomLeft.at<cv::Vec3b>(bottom + 1, 10), rgb(100, 100, 100));
}

TEST(ImageAnnotation, AlphaAndOpacityCompositeOver)
{
    const auto half = imageOf(1, 1, {Rgba{255, 0, 0, 128}});
    // over: 255 * 128/255 + 100 * (1 - 128/255) = 128 + 49.8; green and blue 49.8.
    cv::Vec3b p = rendered(screenImage(half, {5, 5}), test::groundCamera(kWidth, kHeight)).at<cv::Vec3b>(5, 5);
    EXPECT_NEAR(p[2], 178, 2);
    EXPECT_NEAR(p[1], 50, 2);
    EXPECT_NEAR(p[0], 50, 2);
    // Opacity 0.5 on an opaque white pixel: 255 * 0.5 + 100 * 0.5.
    const auto white = imageOf(1, 1, {kWhite});
    p = rendered(screenImage(white, {5, 5}, 0.5), test::groundCamera(kWidth, kHeight)).at<cv::Vec3b>(5, 5);
    EXPECT_NEAR(p[1], 178, 2);
}

// A 4 m x 4 m image on the ground, centred 3 m ahead of the camera's foot; rows along +Y (left), columns along +X.
OverlayScene groundImage()
{
    ImageShape shape;
    shape.image = quadrants(16);
    shape.anchor = glm::dvec3(1.0, 0.0, 0.0);
    shape.size = {4.0, 4.0};
    shape.axisU = {0.0, -1.0, 0.0}; // the image's rows run left to right as seen from the camera (looking +X)
    shape.axisV = {1.0, 0.0, 0.0};  // its top is the far side
    return {{}, {test::annotation("sign", shape, kWhite, 1.0, "ground")}, std::nullopt};
}

cv::Point pixelOf(const Camera &camera, const glm::dvec3 &point)
{
    const glm::dvec3 p =
        glm::projectNO(point, camera.view(), camera.projection().matrix(), glm::dvec4(0, 0, kWidth, kHeight));
    return {int(std::floor(p.x)), int(std::floor(kHeight - p.y))};
}

TEST(ImageAnnotation, WorldImageQuartersLandWhereTheirPlanePointsProject)
{
    const Camera camera = test::groundCamera(kWidth, kHeight);
    const cv::Mat frame = rendered(groundImage(), camera);
    // The middle of each quarter: anchor -+ 1 m across (u) and +- 1 m along (v).
    const struct {
        glm::dvec3 point;
        cv::Vec3b colour;
    } quarters[] = {{{2.0, 1.0, 0.0}, rgb(255, 0, 0)},
                    {{2.0, -1.0, 0.0}, rgb(0, 255, 0)},
                    {{0.0, 1.0, 0.0}, rgb(255, 255, 255)},
                    {{0.0, -1.0, 0.0}, rgb(0, 0, 255)}};
    for (const auto &quarter : quarters) {
        const cv::Point at = pixelOf(camera, quarter.point);
        ASSERT_TRUE(at.x >= 0 && at.y >= 0 && at.x < int(kWidth) && at.y < int(kHeight)) << at;
        EXPECT_EQ(frame.at<cv::Vec3b>(at), quarter.colour) << at;
    }
    // Outside the image (1 m beyond its far edge), the frame is untouched.
    EXPECT_EQ(frame.at<cv::Vec3b>(pixelOf(camera, {4.0, 0.0, 0.0})), rgb(100, 100, 100));
}

TEST(ImageAnnotation, WorldImageFollowsTheCameraItsLayerAndIsLeftOutBehindIt)
{
    const Camera camera = test::groundCamera(kWidth, kHeight);
    auto renderer = test::makeRenderer(groundImage(), camera, test::streamFormat("RGB24", kWidth, kHeight));
    test::TestFrame frame = greyFrame();
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));

    // Turned round (yaw 180): the image is behind the camera, drawn nowhere.
    const auto pose = poseFromYawPitchRoll({-4.0, 0.0, 2.0}, 180.0, 25.0, 0.0);
    auto turned = Camera::create(*pose, camera.projection(), Distortion{}, camera.viewport());
    ASSERT_TRUE(turned.ok());
    ASSERT_TRUE(renderer->setCamera(*turned));
    frame = greyFrame();
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    cv::Mat grey(int(kHeight), int(kWidth), CV_8UC3, cv::Scalar(100, 100, 100));
    EXPECT_EQ(cv::norm(test::toBgr(frame), grey, cv::NORM_INF), 0.0);

    ASSERT_TRUE(renderer->setCamera(camera));
    ASSERT_TRUE(renderer->setLayerEnabled("ground", false));
    frame = greyFrame();
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    EXPECT_EQ(cv::norm(test::toBgr(frame), grey, cv::NORM_INF), 0.0);
    ASSERT_TRUE(renderer->setLayerEnabled("ground", true));
    frame = greyFrame();
    ASSERT_TRUE(renderer->blend(frame.view(), FrameMetadata{}, 30.0));
    EXPECT_EQ(test::toBgr(frame).at<cv::Vec3b>(pixelOf(camera, {2.0, 1.0, 0.0})), rgb(255, 0, 0));
}

} // namespace
} // namespace overlayd
