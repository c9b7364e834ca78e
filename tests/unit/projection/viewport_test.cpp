// SPDX-License-Identifier: Apache-2.0
// viewport_test: NDC -> pixels for top-left and bottom-left origins, windows, scissors and non-square pixels.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/viewport.h"

using namespace overlayd;

namespace {

constexpr int kW = 640, kH = 480;

Viewport make(const ViewportSpec &spec)
{
    auto viewport = Viewport::create(spec);
    EXPECT_TRUE(viewport.ok()) << viewport.error().message;
    return *viewport;
}

void expectPixel(const glm::dvec2 &actual, double x, double y)
{
    EXPECT_NEAR(actual.x, x, 1e-12);
    EXPECT_NEAR(actual.y, y, 1e-12);
}

TEST(Viewport, WholeFrameCornersAndCentreFollowThePixelCentreConvention)
{
    // Pixel (i, j) is centred on (i, j): the frame spans [-0.5, W - 0.5] x [-0.5, H - 0.5].
    const Viewport topLeft = make({kW, kH, std::nullopt, Origin::TopLeft});
    expectPixel(topLeft.ndcToPixel({-1, 1}), -0.5, -0.5); // NDC top-left is memory row 0
    expectPixel(topLeft.ndcToPixel({1, -1}), kW - 0.5, kH - 0.5);
    expectPixel(topLeft.ndcToPixel({0, 0}), (kW - 1) / 2.0, (kH - 1) / 2.0);

    const Viewport bottomLeft = make({kW, kH, std::nullopt, Origin::BottomLeft});
    expectPixel(bottomLeft.ndcToPixel({-1, -1}), -0.5, -0.5); // NDC bottom-left is row 0 counted upwards
    expectPixel(bottomLeft.ndcToPixel({1, 1}), kW - 0.5, kH - 0.5);
    expectPixel(bottomLeft.ndcToPixel({0, 0}), (kW - 1) / 2.0, (kH - 1) / 2.0);
}

TEST(Viewport, TopLeftAndBottomLeftRowsAreMirrored)
{
    const Viewport topLeft = make({kW, kH, std::nullopt, Origin::TopLeft});
    const Viewport bottomLeft = make({kW, kH, std::nullopt, Origin::BottomLeft});
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> ndc(-1.2, 1.2);
    for (int i = 0; i < 200; ++i) {
        const glm::dvec2 q{ndc(rng), ndc(rng)};
        const glm::dvec2 tl = topLeft.ndcToPixel(q), bl = bottomLeft.ndcToPixel(q);
        EXPECT_NEAR(tl.x, bl.x, 1e-12);
        EXPECT_NEAR(tl.y + bl.y, kH - 1.0, 1e-12);
        // toTopLeft turns the bottom-left row into the memory row.
        expectPixel(bottomLeft.toTopLeft(bl), tl.x, tl.y);
        expectPixel(topLeft.toTopLeft(tl), tl.x, tl.y);
    }
}

TEST(Viewport, WindowPositionIsCountedInEachOriginsConvention)
{
    // A 200 x 100 window 100 pixels from the left and 50 from the top (top-left) or bottom (bottom-left) edge.
    const PixelRect window{100, 50, 200, 100};
    const Viewport topLeft = make({kW, kH, window, Origin::TopLeft});
    expectPixel(topLeft.ndcToPixel({-1, 1}), 99.5, 49.5);   // window's top-left corner
    expectPixel(topLeft.ndcToPixel({1, -1}), 299.5, 149.5); // its bottom-right corner
    expectPixel(topLeft.ndcToPixel({0, 0}), 199.5, 99.5);

    const Viewport bottomLeft = make({kW, kH, window, Origin::BottomLeft});
    expectPixel(bottomLeft.ndcToPixel({-1, -1}), 99.5, 49.5); // window's bottom-left corner
    expectPixel(bottomLeft.ndcToPixel({1, 1}), 299.5, 149.5);
    // In memory that window occupies rows H - 150 .. H - 51 from the top.
    expectPixel(bottomLeft.toTopLeft(bottomLeft.ndcToPixel({-1, 1})), 99.5, kH - 150 - 0.5);
    expectPixel(bottomLeft.toTopLeft(bottomLeft.ndcToPixel({1, -1})), 299.5, kH - 50 - 0.5);

    // The same window described from the top: every point lands on the same memory pixel.
    const Viewport mirrored = make({kW, kH, PixelRect{100, kH - 50 - 100, 200, 100}, Origin::TopLeft});
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> ndc(-1.0, 1.0);
    for (int i = 0; i < 100; ++i) {
        const glm::dvec2 q{ndc(rng), ndc(rng)};
        const glm::dvec2 fromBottom = bottomLeft.toTopLeft(bottomLeft.ndcToPixel(q));
        expectPixel(fromBottom, mirrored.ndcToPixel(q).x, mirrored.ndcToPixel(q).y);
        EXPECT_TRUE(bottomLeft.inWindow(bottomLeft.ndcToPixel(q)));
    }
    EXPECT_FALSE(bottomLeft.inWindow({99.0, 60.0}));
    EXPECT_TRUE(bottomLeft.inWindow({100.0, 60.0}));
}

TEST(Viewport, PixelToNdcInvertsNdcToPixel)
{
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> ndc(-3.0, 3.0);
    for (Origin origin : {Origin::TopLeft, Origin::BottomLeft}) {
        for (const auto &window : {std::optional<PixelRect>{}, std::optional<PixelRect>{PixelRect{17, 33, 301, 97}}}) {
            const Viewport viewport = make({kW, kH, window, origin});
            for (int i = 0; i < 100; ++i) {
                const glm::dvec2 q{ndc(rng), ndc(rng)};
                const glm::dvec2 back = viewport.pixelToNdc(viewport.ndcToPixel(q));
                EXPECT_NEAR(back.x, q.x, 1e-12);
                EXPECT_NEAR(back.y, q.y, 1e-12);
            }
            // Pixel centres of the window's first and last pixels are half a pixel inside NDC +-1.
            const PixelRect &w = viewport.window();
            const glm::dvec2 first = viewport.pixelToNdc({w.x, w.y});
            EXPECT_NEAR(first.x, -1.0 + 1.0 / w.width, 1e-12);
            EXPECT_NEAR(first.y, (origin == Origin::TopLeft ? 1.0 : -1.0) * (1.0 - 1.0 / w.height), 1e-12);
        }
    }
}

TEST(Viewport, ScissorTestUsesPixelSquares)
{
    const PixelRect scissor{10, 20, 30, 40};
    const Viewport viewport = make({kW, kH, std::nullopt, Origin::TopLeft, 1.0, scissor});
    EXPECT_EQ(viewport.scissor(), scissor);
    EXPECT_TRUE(viewport.inScissor({10, 20}));
    EXPECT_TRUE(viewport.inScissor({39, 59}));
    EXPECT_TRUE(viewport.inScissor({9.5, 19.5})); // the outer edge of the first pixel
    EXPECT_FALSE(viewport.inScissor({9.4, 30}));
    EXPECT_FALSE(viewport.inScissor({40, 30}));
    EXPECT_FALSE(viewport.inScissor({20, 60}));
    EXPECT_FALSE(viewport.inScissor({20, 19.4}));
    EXPECT_EQ(viewport.scissorTopLeft(), scissor);
}

TEST(Viewport, ScissorDefaultsToTheWindow)
{
    const PixelRect window{100, 50, 200, 100};
    const Viewport viewport = make({kW, kH, window, Origin::BottomLeft});
    EXPECT_EQ(viewport.scissor(), window);
    EXPECT_TRUE(viewport.inScissor(viewport.ndcToPixel({0.99, 0.99})));
    EXPECT_FALSE(viewport.inScissor(viewport.ndcToPixel({1.02, 0.0})));
}

TEST(Viewport, BottomLeftScissorInTopLeftCoordinates)
{
    const PixelRect scissor{10, 20, 30, 40};
    const Viewport viewport = make({kW, kH, std::nullopt, Origin::BottomLeft, 1.0, scissor});
    // Bottom-left rows 20 .. 59 are memory rows H - 60 .. H - 21.
    EXPECT_EQ(viewport.scissorTopLeft(), (PixelRect{10, kH - 60, 30, 40}));
    // A pixel is in the scissor exactly when its memory position is in the top-left scissor rectangle.
    const PixelRect tl = viewport.scissorTopLeft();
    for (int y = 10; y < 70; ++y) {
        for (int x = 0; x < 50; ++x) {
            const glm::dvec2 memory = viewport.toTopLeft({x, y});
            const bool inTl =
                memory.x >= tl.x && memory.x < tl.x + tl.width && memory.y >= tl.y && memory.y < tl.y + tl.height;
            EXPECT_EQ(viewport.inScissor({x, y}), inTl) << x << ", " << y;
        }
    }
}

TEST(Viewport, WindowAspectAccountsForNonSquarePixels)
{
    // The viewing pipeline: camera_ratio = xres * pixelspacing_x / (yres * pixelspacing_y). PAL 720 x 576 with 16:15
    // pixels is a 4:3 picture.
    const Viewport pal = make({720, 576, std::nullopt, Origin::TopLeft, 16.0 / 15.0});
    EXPECT_NEAR(pal.windowAspect(), 4.0 / 3.0, 1e-12);
    const Viewport square = make({kW, kH, PixelRect{0, 0, 300, 200}});
    EXPECT_NEAR(square.windowAspect(), 1.5, 1e-12);

    // A projection given that aspect draws a circle round in physical units on the non-square pixels.
    auto projection =
        Projection::perspective(FovAxis::Vertical, 40.0, pal.windowAspect(), 0.1, 100.0, DepthRange::MinusOneToOne);
    ASSERT_TRUE(projection.ok());
    auto camera = Camera::create(Pose{}, *projection, Distortion{}, pal);
    ASSERT_TRUE(camera.ok());
    const glm::dvec2 centre = camera->project(glm::dvec3(0, 0, -5)).pixel;
    for (int i = 0; i < 12; ++i) {
        const double angle = i * M_PI / 6.0;
        const glm::dvec2 p = camera->project(glm::dvec3(std::cos(angle), std::sin(angle), -5)).pixel;
        // Horizontal pixel steps are 16/15 as wide as vertical ones.
        const double radius = std::hypot((p.x - centre.x) * 16.0 / 15.0, p.y - centre.y);
        EXPECT_NEAR(radius, 0.2 * 576 / 2.0 / std::tan(20.0 * M_PI / 180.0), 1e-9) << "angle " << angle;
    }
}

} // namespace
