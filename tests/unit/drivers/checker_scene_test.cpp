// SPDX-License-Identifier: Apache-2.0
// The checkerboard scene against Camera::project: on either side of every projected checker edge the colour is the
// square's expected shade, for plain and distorting lenses and both viewport origins.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "drivers/source_options.h"
#include "drivers/synthetic/checker_scene.h"
#include "media/convert/frame_convert.h"
#include "test_util.h"

namespace overlayd {
namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr double kSquare = 0.5;

Camera makeCamera(bool distorted, Origin origin)
{
    auto pose = poseLookAt({-3.0, -4.0, 1.6}, {1.0, 0.5, 0.0}, {0.0, 0.0, 1.0});
    const PinholeIntrinsics k{190.0, 190.0, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0, 0.0, kWidth, kHeight};
    auto projection = Projection::pinhole(k, 0.05, 200.0, DepthRange::ZeroToOne);
    ViewportSpec spec{kWidth, kHeight};
    spec.origin = origin;
    auto viewport = Viewport::create(spec);
    Distortion lens{};
    if (distorted)
        lens = Distortion{DistortionModel::RadialTangential, {-0.28, 0.08, 0.0005, -0.0003, -0.01}};
    auto camera = Camera::create(*pose, *projection, lens, *viewport);
    EXPECT_TRUE(camera);
    return *camera;
}

struct Rendered {
    std::vector<uint8_t> rgb; // memory order
    uint8_t red(glm::dvec2 memoryPixel) const
    {
        const int x = int(std::lround(memoryPixel.x)), y = int(std::lround(memoryPixel.y));
        return rgb[(size_t(y) * kWidth + x) * 3];
    }
};

Rendered renderThroughSource(const Camera &camera)
{
    SourceOptions o;
    o.pixelFormat = pixelFormatFromName("RGB24");
    o.width = kWidth, o.height = kHeight;
    o.synthetic.pattern = SyntheticPattern::CheckerboardScene;
    o.synthetic.checkerMetres = kSquare;
    auto source = makeSource(o, &camera);
    EXPECT_TRUE(source);
    EXPECT_TRUE((*source)->start());
    auto lease = (*source)->nextFrame();
    EXPECT_TRUE(lease);
    return {test::visibleBytes(lease->view())};
}

bool inside(glm::dvec2 p)
{
    return p.x >= 2 && p.y >= 2 && p.x <= kWidth - 3 && p.y <= kHeight - 3;
}

// Checks the midpoints of the edges x = i * s (between squares (i-1, j) and (i, j)) and y = j * s; returns how many
// were in view and large enough to test.
int checkEdges(const Camera &camera, const Rendered &image)
{
    int checked = 0;
    const auto memory = [&](const glm::dvec3 &world) {
        return camera.project(world).pixel;
    };
    for (int i = -8; i <= 8; ++i) {
        for (int j = -8; j <= 8; ++j) {
            for (const bool alongX : {true, false}) {
                // Edge point, and points a quarter square into the squares on each side.
                const glm::dvec3 edge = alongX ? glm::dvec3(i * kSquare, (j + 0.5) * kSquare, 0)
                                               : glm::dvec3((i + 0.5) * kSquare, j * kSquare, 0);
                const glm::dvec3 across = alongX ? glm::dvec3(0.25 * kSquare, 0, 0) : glm::dvec3(0, 0.25 * kSquare, 0);
                if (camera.project(edge).status != PointStatus::Visible ||
                    camera.project(edge + across).status != PointStatus::Visible ||
                    camera.project(edge - across).status != PointStatus::Visible)
                    continue;
                const glm::dvec2 p = memory(edge), plus = memory(edge + across), minus = memory(edge - across);
                // Only squares that are large on screen: a pixel 1.5 px from the edge is then wholly inside one.
                if (glm::length(plus - p) < 6.0 || glm::length(minus - p) < 6.0)
                    continue;
                const glm::dvec2 a = p + 1.5 * glm::normalize(plus - p), b = p + 1.5 * glm::normalize(minus - p);
                if (!inside(a) || !inside(b))
                    continue;
                // Square on the + side: (i, j) for an x edge, (i, j) for a y edge; the - side is (i-1, j) / (i, j-1).
                const bool plusDark = ((i + j) & 1) != 0;
                EXPECT_NEAR(image.red(a), plusDark ? kSceneDark[0] : kSceneLight[0], 1) << "edge " << i << "," << j;
                EXPECT_NEAR(image.red(b), plusDark ? kSceneLight[0] : kSceneDark[0], 1) << "edge " << i << "," << j;
                ++checked;
            }
        }
    }
    return checked;
}

TEST(CheckerScene, ColourFlipsAcrossProjectedEdges)
{
    for (const bool distorted : {false, true}) {
        for (const Origin origin : {Origin::TopLeft, Origin::BottomLeft}) {
            SCOPED_TRACE(std::string(distorted ? "distorted" : "pinhole") +
                         (origin == Origin::TopLeft ? " top-left" : " bottom-left"));
            const Camera camera = makeCamera(distorted, origin);
            EXPECT_GE(checkEdges(camera, renderThroughSource(camera)), 40);
        }
    }
}

TEST(CheckerScene, SkyAboveTheHorizon)
{
    const Camera camera = makeCamera(false, Origin::TopLeft);
    const RgbImage image = renderCheckerScene(camera, kWidth, kHeight, kSquare);
    // The camera looks down 1.6 m over ~5.6 m: the horizon is in the top part; the top-left pixel sees sky.
    EXPECT_EQ(image.rgb[0], kSceneSky[0]);
    EXPECT_EQ(image.rgb[1], kSceneSky[1]);
    EXPECT_EQ(image.rgb[2], kSceneSky[2]);
}

// Toward the horizon a pixel sees many squares at once: a camera averages them, so the pixel must be near the mean
// of the two shades, not one of them by chance (moire). The footprint's length along the ground is measured here
// from the rays through the pixel's top and bottom edges: the average of the square wave over 4 squares or more
// lies within 1/8 of its span from grey.
TEST(CheckerScene, FarGroundIsAveragedNotAliased)
{
    const auto pose = poseLookAt({0.0, -6.0, 3.0}, {0.0, 60.0, 0.0}, {0.0, 0.0, 1.0});
    const PinholeIntrinsics k{300.0, 300.0, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0, 0.0, kWidth, kHeight};
    const auto camera = Camera::create(*pose, *Projection::pinhole(k, 0.05, 1000.0, DepthRange::ZeroToOne),
                                       Distortion{}, *Viewport::create(ViewportSpec{kWidth, kHeight}));
    ASSERT_TRUE(camera);
    constexpr double square = 1.0;
    const RgbImage image = renderCheckerScene(*camera, kWidth, kHeight, square);
    const Plane ground = Plane::fromPointNormal({0, 0, 0}, {0, 0, 1});
    const auto groundY = [&](double u, double v) -> std::optional<double> {
        const auto ray = camera->unproject({u, v});
        const auto t = ray ? intersect(*ray, ground) : std::nullopt;
        if (!t)
            return std::nullopt;
        return ray->at(*t).y;
    };
    const double grey = (kSceneLight[0] + kSceneDark[0]) / 2.0, span = kSceneLight[0] - kSceneDark[0];
    int checked = 0, aliased = 0;
    for (int y = 0; y < kHeight; ++y) {
        const auto top = groundY(kWidth / 2.0, y - 0.5), bottom = groundY(kWidth / 2.0, y + 0.5);
        if (!top || !bottom || std::abs(*top - *bottom) < 4.0 * square || std::abs(*top - *bottom) > 1e4)
            continue;
        for (int x = 0; x < kWidth; ++x, ++checked)
            aliased += std::abs(image.rgb[(size_t(y) * kWidth + x) * 3] - grey) > span / 8.0 + 1.0;
    }
    EXPECT_GE(checked, 4 * kWidth) << "the camera must see far ground";
    EXPECT_EQ(aliased, 0) << "of " << checked << " far-ground pixels";
}

TEST(CheckerScene, CameraMustMatchTheFrameSize)
{
    SourceOptions o;
    o.pixelFormat = pixelFormatFromName("YUYV");
    o.width = 640, o.height = 480;
    o.synthetic.pattern = SyntheticPattern::CheckerboardScene;
    const Camera camera = makeCamera(false, Origin::TopLeft);
    auto source = makeSource(o, &camera);
    ASSERT_FALSE(source);
    EXPECT_NE(source.error().message.find("320x240"), std::string::npos) << source.error().message;
    EXPECT_FALSE(makeSource(o));
}

} // namespace
} // namespace overlayd
