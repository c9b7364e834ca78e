// SPDX-License-Identifier: Apache-2.0
// Every example under config/examples/ loads without a problem and builds its camera; the README's demo has the
// scene the README promises.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include "config_test_util.h"

namespace overlayd::test {
namespace {

DaemonConfig loadExample(const std::string &name)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(sourceDir() + "/config/examples/" + name, problems);
    std::string all;
    for (const ConfigProblem &p : problems)
        all += p.format() + "\n";
    EXPECT_TRUE(config.ok()) << all;
    return config ? config.value() : DaemonConfig{};
}

TEST(Examples, EveryExampleLoadsAndBuildsItsCamera)
{
    int count = 0;
    for (const auto &entry : std::filesystem::directory_iterator(sourceDir() + "/config/examples")) {
        if (entry.path().extension() != ".toml")
            continue;
        SCOPED_TRACE(entry.path().filename().string());
        const DaemonConfig config = loadExample(entry.path().filename().string());
        auto camera = config.camera.build(config.source.width, config.source.height);
        EXPECT_TRUE(camera.ok()) << (camera ? "" : camera.error().message);
        ++count;
    }
    EXPECT_GE(count, 7);
}

template<typename T>
std::vector<const T *> shapesOf(const DaemonConfig &config)
{
    std::vector<const T *> out;
    for (const Annotation &a : config.scene.annotations)
        if (const T *shape = std::get_if<T>(&a.shape))
            out.push_back(shape);
    return out;
}

TEST(Examples, DemoIsTheReadmeScene)
{
    const DaemonConfig config = loadExample("demo.toml");
    EXPECT_EQ(config.source.kind, SourceKind::Synthetic);
    EXPECT_EQ(config.source.pixelFormat->name, "YUYV");
    EXPECT_EQ(config.source.width, 1280u);
    EXPECT_EQ(config.source.height, 720u);
    EXPECT_EQ(config.source.synthetic.pattern, SyntheticPattern::CheckerboardScene);
    EXPECT_EQ(config.source.synthetic.checkerMetres, 1.0);
    const auto grids = shapesOf<GridShape>(config);
    ASSERT_EQ(grids.size(), 1u);
    EXPECT_EQ(grids[0]->spacing, config.source.synthetic.checkerMetres); // lines on the checker edges
    EXPECT_EQ(grids[0]->origin, glm::dvec3(0.0));
    EXPECT_EQ(shapesOf<AxesShape>(config).size(), 1u);
    EXPECT_GE(shapesOf<LabelShape>(config).size(), 2u);
    const auto texts = shapesOf<ScreenTextShape>(config);
    ASSERT_EQ(texts.size(), 2u);
    EXPECT_EQ(texts[0]->text, "{time:%Y-%m-%d %H:%M:%S}");
    EXPECT_NE(texts[1]->text.find("{frame}"), std::string::npos);
    ASSERT_EQ(config.sinks.size(), 2u);
    EXPECT_EQ(config.sinks[0].kind, SinkKind::Y4m);
    EXPECT_EQ(config.sinks[0].path, "out/demo.y4m");
    EXPECT_EQ(config.sinks[1].kind, SinkKind::Snapshot);
    EXPECT_EQ(config.sinks[1].path, "out/demo-%04d.png");
    EXPECT_EQ(config.sinks[1].every, 30u);
}

TEST(Examples, DemoCameraLooksDownAtTheGround)
{
    const DaemonConfig config = loadExample("demo.toml");
    auto camera = config.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok());
    EXPECT_NEAR(camera->position().z, 3.0, 1e-12);
    // The image centre's ray goes down and meets the ground in front of the camera.
    auto ray = camera->unproject(glm::dvec2(639.5, 359.5));
    ASSERT_TRUE(ray.ok());
    EXPECT_LT(ray->direction.z, 0.0);
    EXPECT_GT(ray->direction.y, 0.0);
    EXPECT_EQ(camera->project(glm::dvec3(0, 0, 0)).status, PointStatus::Visible);
    EXPECT_EQ(camera->project(glm::dvec3(2, 5, 0)).status, PointStatus::Visible);
}

// The axes triad reads as three axes: the Y axis (away from the camera) is not drawn over the Z axis (up), as it is
// from any camera in their plane x = 0. Compared by the directions of the drawn axes from the origin's pixel.
TEST(Examples, DemoDrawsTheYAxisApartFromTheZAxis)
{
    const DaemonConfig config = loadExample("demo.toml");
    auto camera = config.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok());
    const auto origin = camera->project(glm::dvec3(0, 0, 0)), y = camera->project(glm::dvec3(0, 1, 0)),
               z = camera->project(glm::dvec3(0, 0, 1));
    ASSERT_TRUE(origin.status == PointStatus::Visible && y.status == PointStatus::Visible &&
                z.status == PointStatus::Visible);
    const glm::dvec2 alongY = glm::normalize(y.pixel - origin.pixel), alongZ = glm::normalize(z.pixel - origin.pixel);
    const double degrees = glm::degrees(std::acos(std::clamp(glm::dot(alongY, alongZ), -1.0, 1.0)));
    EXPECT_GT(degrees, 15.0) << "the Y and Z axes are drawn " << degrees << " degrees apart";
}

TEST(Examples, DistortedPinholeComesFromItsCalibration)
{
    const DaemonConfig config = loadExample("distorted_pinhole.toml");
    EXPECT_EQ(config.camera.form, IntrinsicsForm::Pinhole);
    EXPECT_EQ(config.camera.distortion.model, DistortionModel::RadialTangential);
    EXPECT_DOUBLE_EQ(config.camera.distortion.coeffs[0], -0.28);
    EXPECT_DOUBLE_EQ(config.camera.pinhole.fx, 821.5); // overridden in the TOML
    EXPECT_DOUBLE_EQ(config.camera.pinhole.fy, 818.0); // from the calibration
    auto camera = config.camera.build(1280, 720);
    ASSERT_TRUE(camera.ok());
    // The rvec/tvec in the example put the camera 2.5 m above the origin.
    EXPECT_NEAR(glm::length(camera->position() - glm::dvec3(0, 0, 2.5)), 0.0, 1e-9);
}

TEST(Examples, OtherExamplesUseTheirFeature)
{
    EXPECT_EQ(loadExample("orthographic.toml").camera.form, IntrinsicsForm::Orthographic);
    EXPECT_EQ(loadExample("bottom_left.toml").camera.viewport.origin, Origin::BottomLeft);
    EXPECT_EQ(loadExample("v4l2_camera.toml").source.kind, SourceKind::V4l2);
    EXPECT_EQ(loadExample("v4l2_camera.toml").source.v4l2.device, "/dev/video0");
    const DaemonConfig replay = loadExample("replay.toml");
    EXPECT_EQ(replay.source.kind, SourceKind::Replay);
    EXPECT_EQ(replay.source.replay.path, sourceDir() + "/config/examples/recorded.y4m");
    const DaemonConfig images = loadExample("images.toml");
    ASSERT_EQ(shapesOf<ImageShape>(images).size(), 2u);
    EXPECT_EQ(shapesOf<ImageShape>(images)[0]->image->width, 160u);
    const DaemonConfig reverse = loadExample("reverse_camera.toml");
    EXPECT_EQ(reverse.camera.mountFrame, "car");
    EXPECT_EQ(shapesOf<GuideLinesShape>(reverse).size(), 1u);
    ASSERT_EQ(reverse.inputs.can.size(), 1u);
    EXPECT_EQ(reverse.inputs.can[0].target.name, "guide lines");
}

} // namespace
} // namespace overlayd::test
