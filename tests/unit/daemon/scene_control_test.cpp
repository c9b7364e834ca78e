// SPDX-License-Identifier: Apache-2.0
// SceneControl: each change is validated before anything changes, reaches the live renderer, and survives the
// renderer being rebuilt for a new stream.
#include "control/scene_control.h"

#include <utility>

#include <gtest/gtest.h>

#include "fakes.h"

namespace overlayd {
namespace {

OverlayScene twoLayers()
{
    OverlayScene scene;
    Annotation grid{"grid", "world", {}, GridShape{}};
    grid.style.layer = "grid";
    Annotation label{"label", "world", {}, AxesShape{}};
    label.style.layer = "labels";
    Annotation gear{"gear", "world", {}, ScreenTextShape{"gear {slot:gear} {frame}"}};
    gear.style.layer = "labels";
    scene.annotations = {grid, label, grid, gear};
    return scene;
}

struct SceneControlTest : ::testing::Test {
    bool factoryFails = false;
    test::RecordingRenderer *last = nullptr; // the renderer the factory made last
    SceneControl control{[this](const OverlayScene &scene, const Camera &,
                                const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
        if (factoryFails)
            return makeError(ErrorCode::InvalidArgument, "annotation 'x': unknown frame 'base'");
        if (scene.annotations.empty())
            return std::unique_ptr<OverlayRenderer>();
        auto renderer = std::make_unique<test::RecordingRenderer>();
        last = renderer.get();
        return std::unique_ptr<OverlayRenderer>(std::move(renderer));
    }};
    std::unique_ptr<OverlayRenderer> live;

    void SetUp() override
    {
        control.load(twoLayers(), CameraSpec{});
        open();
    }
    // A stream opens: the pipeline takes the built renderer and SceneControl is attached to it.
    void open()
    {
        auto built = control.build(test::greyFormat());
        ASSERT_TRUE(built.ok());
        live = std::move(*built);
        control.attach(live.get(), test::greyFormat());
    }
};

TEST_F(SceneControlTest, CameraChangeIsValidatedAsTheConfigIsAndRefusedWhole)
{
    CameraSpec bad;
    bad.fovDeg = 190.0; // what check-config refuses for [camera] fov
    const Status refused = control.apply(CameraChange{bad});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("camera: "), std::string::npos) << refused.error().message;
    EXPECT_TRUE(last->cameras.empty());
    EXPECT_EQ(control.camera().fovDeg, 60.0);

    CameraSpec narrower;
    narrower.fovDeg = 30.0;
    ASSERT_TRUE(control.apply(CameraChange{narrower}).ok());
    ASSERT_EQ(last->cameras.size(), 1u);
    // A narrower field of view: a larger focal term in the projection matrix (cot(15 deg) = 3.73).
    EXPECT_NEAR(last->cameras[0][1][1], 1.0 / std::tan(15.0 * M_PI / 180.0), 1e-12);
    EXPECT_EQ(control.camera().fovDeg, 30.0);
}

TEST_F(SceneControlTest, UnknownLayerIsRefusedNamingTheSceneLayers)
{
    const Status refused = control.apply(LayerChange{"guides", false});
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(refused.error().message, "unknown layer 'guides' (the scene has: grid, labels)");
    EXPECT_TRUE(last->layers.empty());
    EXPECT_TRUE(control.layerVisible("grid"));
}

TEST_F(SceneControlTest, LayerChoiceReachesTheRendererAndSurvivesARebuild)
{
    ASSERT_TRUE(control.apply(LayerChange{"labels", false}).ok());
    ASSERT_EQ(last->layers.size(), 1u);
    EXPECT_EQ(last->layers[0], std::pair(std::string("labels"), false));
    EXPECT_FALSE(control.layerVisible("labels"));

    open(); // the source re-opened: a new renderer for the new stream
    ASSERT_EQ(last->layers.size(), 1u);
    EXPECT_EQ(last->layers[0], std::pair(std::string("labels"), false));
}

TEST_F(SceneControlTest, SlotTextIsCheckedReachesTheRendererAndSurvivesARebuild)
{
    const Status unknown = control.apply(TextChange{"speed", "12"});
    ASSERT_FALSE(unknown.ok());
    EXPECT_EQ(unknown.error().message, "unknown text slot 'speed' (the scene has: gear)");
    EXPECT_FALSE(control.apply(TextChange{"gear", "R\nD"}).ok());
    EXPECT_FALSE(control.apply(TextChange{"gear", std::string(kMaxSlotTextBytes + 1, 'R')}).ok());
    EXPECT_TRUE(last->slots.empty());
    EXPECT_EQ(control.slotText("gear"), "");

    ASSERT_TRUE(control.apply(TextChange{"gear", "R"}).ok());
    ASSERT_EQ(last->slots.size(), 1u);
    EXPECT_EQ(last->slots[0], std::pair(std::string("gear"), std::string("R")));
    EXPECT_EQ(control.slotText("gear"), "R");
    open();
    ASSERT_EQ(last->slots.size(), 1u);
    EXPECT_EQ(last->slots[0], std::pair(std::string("gear"), std::string("R")));
}

TEST_F(SceneControlTest, ReloadCandidateLeavesTheLiveSceneAloneUntilAssigned)
{
    ASSERT_TRUE(control.apply(LayerChange{"grid", false}).ok());
    ASSERT_TRUE(control.apply(TextChange{"gear", "R"}).ok());
    test::RecordingRenderer *running = last;
    OverlayScene next = twoLayers();
    next.annotations.pop_back();
    SceneControl candidate = control.withScene(next, CameraSpec{});

    factoryFails = true;
    const auto refused = candidate.build(test::greyFormat());
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message, "overlay: annotation 'x': unknown frame 'base'");
    EXPECT_EQ(control.scene().annotations.size(), 4u); // a refused reload drops the candidate: nothing changed

    factoryFails = false;
    auto built = candidate.build(test::greyFormat());
    ASSERT_TRUE(built.ok());
    EXPECT_NE(last, running);
    // The live layer choices and slot texts carry over into the new overlay.
    EXPECT_EQ(last->layers, (std::vector<std::pair<std::string, bool>>{{"grid", false}}));
    EXPECT_EQ(last->slots, (std::vector<std::pair<std::string, std::string>>{{"gear", "R"}}));
    EXPECT_EQ(control.scene().annotations.size(), 4u);

    // The switch: the candidate becomes the live control, and changes go to the new overlay.
    control = std::move(candidate);
    // The old overlay is kept (not destroyed) so that `running` can still be asked what reached it.
    const std::unique_ptr<OverlayRenderer> retired = std::exchange(live, std::move(*built));
    control.attach(live.get(), test::greyFormat());
    EXPECT_EQ(control.scene().annotations.size(), 3u);
    ASSERT_TRUE(control.apply(LayerChange{"labels", false}).ok());
    EXPECT_EQ(last->layers.back(), std::pair(std::string("labels"), false));
    EXPECT_EQ(running->layers.size(), 1u);
}

TEST_F(SceneControlTest, CameraChangeWithoutAStreamIsRefused)
{
    control.detach();
    const Status refused = control.apply(CameraChange{CameraSpec{}});
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::TryAgain);
}

} // namespace
} // namespace overlayd
