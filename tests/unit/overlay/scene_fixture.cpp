// SPDX-License-Identifier: Apache-2.0
// The renderer tests' camera, scene and stream helpers.
#include "scene_fixture.h"

#include <gtest/gtest.h>

#include "overlay/shapes/scene_checks.h"

namespace overlayd::test {

Camera groundCamera(unsigned width, unsigned height, Origin origin, const Distortion &distortion)
{
    const PinholeIntrinsics k{0.8 * width, 0.8 * width, (width - 1) / 2.0, (height - 1) / 2.0,
                              0.0,         int(width),  int(height)};
    const auto projection = Projection::pinhole(k, 0.1, 100.0, DepthRange::MinusOneToOne);
    const auto pose = poseFromYawPitchRoll({-4.0, 0.0, 2.0}, 0.0, 25.0, 0.0);
    const auto viewport = Viewport::create(ViewportSpec{int(width), int(height), std::nullopt, origin});
    auto camera = Camera::create(*pose, *projection, distortion, *viewport);
    EXPECT_TRUE(camera.ok()) << (camera ? "" : camera.error().message);
    return *camera;
}

Annotation annotation(const std::string &name, Shape shape, Rgba colour, double width, const std::string &layer)
{
    Annotation a{name, SceneGraph::kWorld, Style{}, std::move(shape)};
    a.style.colour = colour;
    a.style.width = width;
    a.style.layer = layer;
    return a;
}

OverlayScene demoScene(bool withText)
{
    OverlayScene scene;
    scene.frames.push_back({"car", "world", Transform{{-1.0, 0.5, 0.0}, glm::angleAxis(0.2, glm::dvec3(0, 0, 1))}});
    GridShape grid;
    grid.extentU = grid.extentV = 5.0;
    grid.majorEvery = 5;
    grid.majorStyle = Style{Rgba{255, 255, 0, 255}, 3.0};
    scene.annotations.push_back(annotation("grid", grid, Rgba{200, 200, 200, 160}, 1.5, "grid"));
    scene.annotations.push_back(annotation("axes", AxesShape{1.0, {kRed, kGreen, kBlue}, withText}, kWhite, 3.0));
    scene.annotations.push_back(annotation("box", BoxShape{{1.5, -1.0, 0.5}, {1.0, 0.6, 1.0}}, Rgba{255, 0, 255, 255}));
    Annotation guide = annotation("guide", GuideLinesShape{2.7, 1.6, 15.0, 4.0, {1.0, 2.0}, {kRed, kGreen}},
                                  Rgba{255, 200, 0, 255}, 2.5, "guide");
    guide.frame = "car";
    guide.style.dash = {12.0, 6.0};
    scene.annotations.push_back(guide);
    scene.annotations.push_back(
        annotation("markers", MarkersShape{{{0.0, 2.0, 0.0}, {2.0, 2.0, 0.0}}, MarkerKind::Circle, 12.0}, kWhite, 1.0));
    scene.annotations.push_back(
        annotation("arc", ArcShape{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1.5, 0.0, 270.0}, Rgba{0, 255, 255, 255}));
    scene.annotations.push_back(annotation("rect", RectShape{{250.0, 20.0}, {40.0, 20.0}, true}, Rgba{0, 0, 255, 128}));
    if (withText) {
        scene.annotations.push_back(
            annotation("label", LabelShape{{0.0, 0.0, 0.0}, "origin", {5.0, 5.0}, 14.0}, kWhite));
        scene.annotations.push_back(annotation(
            "stamp", ScreenTextShape{"frame {frame}", {8.0, 8.0}, 16.0, Rgba{0, 0, 0, 160}}, kWhite, 2.0, "text"));
    }
    return scene;
}

StreamFormat streamFormat(const std::string &formatName, unsigned width, unsigned height)
{
    StreamFormat format;
    format.format = pixelFormatFromName(formatName);
    format.width = width;
    format.height = height;
    format.colorimetry = Colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited};
    return format;
}

std::unique_ptr<SceneRenderer> makeRenderer(const OverlayScene &scene, const Camera &camera, const StreamFormat &format)
{
    auto graph = SceneGraph::create(scene.frames);
    EXPECT_TRUE(graph.ok());
    EXPECT_TRUE(checkScene(scene, *graph).ok());
    auto renderer = std::make_unique<SceneRenderer>(scene, std::move(*graph), camera, format);
    const Status status = renderer->renderWorld();
    EXPECT_TRUE(status.ok()) << (status ? "" : status.error().message);
    return renderer;
}

cv::Mat layerAlpha(const OverlayLayer &layer)
{
    const cv::Mat rgba(int(layer.height()), int(layer.width()), CV_8UC4, const_cast<uint8_t *>(layer.data()));
    cv::Mat alpha;
    cv::extractChannel(rgba, alpha, 3);
    return alpha;
}

TestFrame greyFrame(const std::string &formatName, unsigned width, unsigned height, unsigned stridePadding)
{
    TestFrame frame = makeFrame(formatName, width, height, stridePadding);
    fillRgb(frame, Colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited}, 110, 120, 130);
    return frame;
}

std::vector<std::string> formatNames()
{
    std::vector<std::string> names;
    for (const PixelFormatInfo &info : pixelFormats())
        names.emplace_back(info.name);
    return names;
}

std::string formatName(const testing::TestParamInfo<std::string> &param)
{
    return param.param;
}

} // namespace overlayd::test
