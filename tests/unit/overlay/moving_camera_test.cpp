// SPDX-License-Identifier: Apache-2.0
// A camera that changes before every frame is drawn straight into the frame (FrameCoverageSink); one that holds
// still goes back to the cached layers. Both must show the same overlay: the direct frame is compared with a fresh
// renderer's cached frame for the same camera, in every format, at an odd size with padded strides.
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "scene_fixture.h"

namespace overlayd {
namespace {

using test::TestFrame;

constexpr unsigned kWidth = 101, kHeight = 67, kPadding = 6;
// The cached path averages the composite of all items over a macropixel, the direct path each item on its own:
// they differ where two items of different colours share a macropixel (measured: a few per cent of the pixels, by
// up to ~70 codes at a red-on-white axis edge in NV12), and by a code of rounding elsewhere.
constexpr int kCloseCodes = 3;
constexpr double kMaxFarFraction = 0.04;

class MovingCamera : public testing::TestWithParam<std::string>
{};

TestFrame greyFrame(const std::string &format)
{
    return test::greyFrame(format, kWidth, kHeight, kPadding);
}

// Blends with `renderer` after moving it through two other cameras, so that the last blend draws directly.
TestFrame blendMoving(SceneRenderer &renderer, const std::string &format, const Camera &camera)
{
    TestFrame scratch = greyFrame(format), frame = greyFrame(format);
    EXPECT_TRUE(renderer.setCamera(test::groundCamera(kWidth, kHeight, Origin::BottomLeft)));
    EXPECT_TRUE(renderer.blend(scratch.view(), FrameMetadata{}, 30.0));
    EXPECT_TRUE(renderer.setCamera(camera));
    EXPECT_TRUE(renderer.blend(frame.view(), FrameMetadata{}, 30.0));
    return frame;
}

// The reference: a fresh renderer for `camera`, one blend through its cached layers.
TestFrame cachedFrame(const std::string &format, const OverlayScene &scene, const Camera &camera)
{
    auto still = test::makeRenderer(scene, camera, test::streamFormat(format, kWidth, kHeight));
    TestFrame cached = greyFrame(format);
    EXPECT_TRUE(still->blend(cached.view(), FrameMetadata{}, 30.0));
    EXPECT_FALSE(still->drewDirectly());
    return cached;
}

// A renderer that starts at another camera (the bottom-left origin's).
std::unique_ptr<SceneRenderer> movingRenderer(const std::string &format, const OverlayScene &scene)
{
    return test::makeRenderer(scene, test::groundCamera(kWidth, kHeight, Origin::BottomLeft),
                              test::streamFormat(format, kWidth, kHeight));
}

// The demo scene in one format: the cached reference for the ground camera, and a renderer that starts elsewhere.
struct MovingDemo {
    explicit MovingDemo(const std::string &name)
        : format(name), cached(cachedFrame(format, scene, camera)), moving(movingRenderer(format, scene))
    {}

    std::string format;
    Camera camera = test::groundCamera(kWidth, kHeight);
    OverlayScene scene = test::demoScene(true);
    TestFrame cached;
    std::unique_ptr<SceneRenderer> moving;
};

TEST_P(MovingCamera, DirectFrameMatchesCachedFrame)
{
    MovingDemo demo(GetParam());
    const std::string &format = demo.format;
    const TestFrame &cached = demo.cached;
    SceneRenderer *moving = demo.moving.get();
    const Camera &camera = demo.camera;
    const TestFrame before = greyFrame(format);
    TestFrame direct = blendMoving(*moving, format, camera);
    ASSERT_TRUE(moving->drewDirectly());
    ASSERT_TRUE(direct.guardIntact());

    // Padding is never written.
    const PixelFormatInfo &info = test::format(format);
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        const unsigned visible = info.minStride(p, kWidth);
        for (unsigned row = 0; row < info.planeHeight(p, kHeight); ++row) {
            for (unsigned col = visible; col < direct.stride(p); ++col) {
                const size_t at = direct.layout.planes[p].offset + size_t(row) * direct.stride(p) + col;
                ASSERT_EQ(direct.bytes[at], before.bytes[at]) << "padding: plane " << p << " row " << row;
            }
        }
    }

    cv::Mat diff;
    cv::absdiff(test::toBgr(direct), test::toBgr(cached), diff);
    diff = diff.reshape(1, int(kHeight * kWidth));
    cv::Mat worst;
    cv::reduce(diff, worst, 1, cv::REDUCE_MAX);
    const int far = cv::countNonZero(worst > kCloseCodes);
    EXPECT_LE(far, kMaxFarFraction * kWidth * kHeight) << format << ": pixels off by more than " << kCloseCodes;
    // The overlay is there in both (a direct path that drew nothing would "match" a blank cached frame only if the
    // cached one were blank too).
    cv::Mat changed;
    cv::absdiff(test::toBgr(direct), test::toBgr(before), changed);
    EXPECT_GT(cv::countNonZero(changed.reshape(1, int(kHeight * kWidth * 3)) > 8), 300);
}

// Holding still for one frame renders the cached layers again: the frame is then byte-identical to a fresh
// renderer's.
TEST_P(MovingCamera, HoldingStillReturnsToTheCache)
{
    MovingDemo demo(GetParam());
    SceneRenderer &moving = *demo.moving;
    blendMoving(moving, demo.format, demo.camera);
    ASSERT_TRUE(moving.drewDirectly());
    for (int i = 0; i < 2; ++i) {
        TestFrame again = greyFrame(demo.format);
        ASSERT_TRUE(moving.blend(again.view(), FrameMetadata{}, 30.0));
        EXPECT_FALSE(moving.drewDirectly());
        EXPECT_EQ(again.bytes, demo.cached.bytes) << demo.format << " frame " << i;
    }
}

// Layers switched off stay off while the camera moves.
TEST_P(MovingCamera, DisabledLayersAreNotDrawn)
{
    const std::string &format = GetParam();
    OverlayScene scene = test::demoScene(false);
    auto moving = movingRenderer(format, scene);
    for (const std::string &name : moving->layerNames())
        ASSERT_TRUE(moving->setLayerEnabled(name, false));
    const TestFrame before = greyFrame(format);
    const TestFrame direct = blendMoving(*moving, format, test::groundCamera(kWidth, kHeight));
    ASSERT_TRUE(moving->drewDirectly());
    EXPECT_EQ(direct.bytes, before.bytes);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, MovingCamera, testing::ValuesIn(test::formatNames()), test::formatName);

} // namespace
} // namespace overlayd
