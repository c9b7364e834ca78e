// SPDX-License-Identifier: Apache-2.0
// batch_projection_test: every batch loop of Camera::projectPoints against the single-point Camera::project.
//
// project() is the reference here (it is itself held to OpenCV by opencv_compare_test). The batch loops must give
// the same status and the same pixel and depth (within 1e-9 px, and then bit for bit), for every lens model, on random
// cameras, for points in front, behind, beyond far, outside the lens's valid field and right on the scissor's edges.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

using test::CvCamera;
using test::uniform;

constexpr double kPixelTolerance = 1e-9;

struct Case {
    DistortionModel model;
    BatchKernel kernel;
};

const char *kernelName(BatchKernel kernel)
{
    switch (kernel) {
    case BatchKernel::Best:
        return "Best";
    case BatchKernel::Lanes2:
        return "Lanes2";
    case BatchKernel::Lanes4Avx2:
        return "Lanes4Avx2";
    case BatchKernel::Lanes8Avx512:
        return "Lanes8Avx512";
    }
    return "?";
}

// A camera with a scissor rectangle inside the image (so that its edges are not the image's) on half the draws.
Camera randomCamera(std::mt19937_64 &rng, const CvCamera &c, int index)
{
    const DepthRange depth = index % 2 ? DepthRange::ZeroToOne : DepthRange::MinusOneToOne;
    ViewportSpec spec{c.width, c.height};
    spec.origin = index % 3 ? Origin::TopLeft : Origin::BottomLeft;
    if (index % 4 < 2) {
        const int x = std::uniform_int_distribution<int>(0, c.width / 3)(rng);
        const int y = std::uniform_int_distribution<int>(0, c.height / 3)(rng);
        spec.scissor = PixelRect{x, y, c.width / 2, c.height / 2};
    }
    return test::makeCamera(c, depth, 0.05, 200.0, &spec);
}

// Points that land exactly on (or a rounding error from) the scissor's edges and corners: unprojected edge pixels.
void addScissorEdgePoints(std::mt19937_64 &rng, const Camera &camera, std::vector<glm::dvec3> &world)
{
    const PixelRect s = camera.viewport().scissor();
    const double left = s.x - 0.5, right = s.x + s.width - 0.5, top = s.y - 0.5, bottom = s.y + s.height - 0.5;
    for (int i = 0; i < 40; ++i) {
        const double u = uniform(rng, left, right), v = uniform(rng, top, bottom);
        const glm::dvec2 pixels[] = {{left, v}, {right, v}, {u, top}, {u, bottom}, {left, top}, {right, bottom}};
        for (const glm::dvec2 &pixel : pixels) {
            auto ray = camera.unproject(pixel);
            if (ray)
                world.push_back(ray->origin + uniform(rng, 0.5, 50.0) * ray->direction);
        }
    }
}

std::vector<glm::dvec3> randomPoints(std::mt19937_64 &rng, const CvCamera &c, const Camera &camera)
{
    std::vector<glm::dvec3> world;
    const double radius = test::testFieldRadius(camera);
    const double beyondLens = camera.lens() ? 1.5 * camera.lens()->validRadius() : 4.0;
    for (int i = 0; i < 150; ++i) {
        world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 0.06, 190.0)));
        world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, -50.0, 0.01)));  // behind
        world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, radius, 150.0, 400.0))); // far
        world.push_back(test::worldFromOptical(c, test::randomOpticalPoint(rng, beyondLens, 0.5, 20.0)));
    }
    // Exactly on the near plane and the camera centre itself.
    world.push_back(test::worldFromOptical(c, {0.0, 0.0, 0.05}));
    world.push_back(test::worldFromOptical(c, {0.0, 0.0, 0.0}));
    world.push_back(test::worldFromOptical(c, {0.0, 0.0, 1.0})); // on the optical axis: r = 0
    addScissorEdgePoints(rng, camera, world);
    std::shuffle(world.begin(), world.end(), rng);
    return world;
}

class BatchProjection : public ::testing::TestWithParam<Case>
{
protected:
    void SetUp() override
    {
        if (!Camera::batchKernelAvailable(GetParam().kernel))
            GTEST_SKIP() << kernelName(GetParam().kernel) << " does not run on this CPU";
    }
};

void expectSame(const ProjectedPoint &batch, const ProjectedPoint &single, const std::string &where)
{
    ASSERT_EQ(batch.status, single.status) << where;
    if (single.status == PointStatus::Clipped) {
        EXPECT_EQ(batch.pixel, glm::dvec2(0.0)) << where;
        EXPECT_EQ(batch.depth, 0.0) << where;
        return;
    }
    EXPECT_LE(glm::length(batch.pixel - single.pixel), kPixelTolerance) << where;
    EXPECT_LE(std::abs(batch.depth - single.depth), 1e-15 * std::max(1.0, std::abs(single.depth))) << where;
}

bool sameBits(const ProjectedPoint &a, const ProjectedPoint &b)
{
    return std::bit_cast<std::uint64_t>(a.pixel.x) == std::bit_cast<std::uint64_t>(b.pixel.x) &&
           std::bit_cast<std::uint64_t>(a.pixel.y) == std::bit_cast<std::uint64_t>(b.pixel.y) &&
           std::bit_cast<std::uint64_t>(a.depth) == std::bit_cast<std::uint64_t>(b.depth) && a.status == b.status;
}

// Close, and then bit for bit: every loop runs the single-point kernel's operations in the same order (no fused
// multiply-add), so the doubles must be identical, not merely close; a loop that the compiler or a rewrite
// contracted, reassociated or approximated differently shows here.
TEST_P(BatchProjection, EqualsSinglePointProjection)
{
    const auto [model, kernel] = GetParam();
    std::mt19937_64 rng(0xba7c4 + 16 * static_cast<int>(model) + static_cast<int>(kernel));
    int counts[3] = {0, 0, 0};
    int differentBits = 0;
    for (int cam = 0; cam < 60; ++cam) {
        const CvCamera c = test::randomCvCamera(rng, model);
        const Camera camera = randomCamera(rng, c, cam);
        const std::vector<glm::dvec3> world = randomPoints(rng, c, camera);
        std::vector<ProjectedPoint> batch(world.size());
        camera.projectPoints(world, batch, kernel);
        for (std::size_t i = 0; i < world.size(); ++i) {
            const ProjectedPoint single = camera.project(world[i]);
            expectSame(batch[i], single, "camera " + std::to_string(cam) + " point " + std::to_string(i));
            counts[static_cast<int>(single.status)]++;
            if (!sameBits(batch[i], single) && differentBits++ < 3)
                ADD_FAILURE() << "camera " << cam << " point " << i << ": (" << batch[i].pixel.x << ", "
                              << batch[i].pixel.y << ", " << batch[i].depth << ") differs in its bits from project()";
        }
    }
    EXPECT_EQ(differentBits, 0) << "points whose bits differ from project()";
    // Every status must have been exercised, or the comparison proves little.
    EXPECT_GT(counts[static_cast<int>(PointStatus::Clipped)], 2000);
    EXPECT_GT(counts[static_cast<int>(PointStatus::Outside)], 1000);
    EXPECT_GT(counts[static_cast<int>(PointStatus::Visible)], 1000);
}

// Counts that are not a multiple of any lane count, outputs at odd offsets, and an output longer than the input.
TEST_P(BatchProjection, AnyCountAndOffset)
{
    const auto [model, kernel] = GetParam();
    std::mt19937_64 rng(0x7a11 + static_cast<int>(model));
    const CvCamera c = test::randomCvCamera(rng, model);
    const Camera camera = randomCamera(rng, c, 1);
    const std::vector<glm::dvec3> all = randomPoints(rng, c, camera);
    const ProjectedPoint sentinel{{-7.0, -7.0}, -7.0, PointStatus::Visible};
    for (std::size_t count = 0; count <= 19; ++count) {
        for (std::size_t offset : {0, 1, 3}) {
            std::vector<ProjectedPoint> out(count + offset + 2, sentinel);
            const std::span<const glm::dvec3> world(all.data() + offset, count);
            camera.projectPoints(world, std::span(out).subspan(offset), kernel);
            for (std::size_t i = 0; i < offset; ++i)
                EXPECT_EQ(out[i].depth, -7.0) << "written before the output span";
            for (std::size_t i = 0; i < count; ++i)
                expectSame(out[offset + i], camera.project(world[i]), "count " + std::to_string(count));
            EXPECT_EQ(out[offset + count].depth, -7.0) << "count " << count << ": written past the input's end";
        }
    }
}

// NaN and infinite coordinates are clipped (w > 0 refuses NaN) in both forms, never a garbage pixel.
TEST_P(BatchProjection, NonFiniteInputIsClippedLikeProject)
{
    const auto [model, kernel] = GetParam();
    std::mt19937_64 rng(0x1af + static_cast<int>(model));
    const CvCamera c = test::randomCvCamera(rng, model);
    const Camera camera = randomCamera(rng, c, 2);
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<glm::dvec3> world = {{nan, 0, 0}, {0, nan, 1},           {inf, 1, 2},         {1, -inf, 2},
                                           {0, 0, inf}, {1e300, 1e300, 1e300}, {-1e-300, 1e-300, 0}};
    std::vector<ProjectedPoint> batch(world.size());
    camera.projectPoints(world, batch, kernel);
    for (std::size_t i = 0; i < world.size(); ++i) {
        const ProjectedPoint single = camera.project(world[i]);
        expectSame(batch[i], single, "point " + std::to_string(i));
        if (!std::isfinite(world[i].x) || !std::isfinite(world[i].y) || !std::isfinite(world[i].z)) {
            EXPECT_EQ(single.status, PointStatus::Clipped) << "point " << i;
        }
    }
}

std::vector<Case> allCases()
{
    // The x86-64 loops exist only in an x86-64 build (on arm64 there is nothing to skip); on an x86-64 CPU without
    // AVX2 / AVX-512F their cases report themselves skipped.
    std::vector<BatchKernel> kernels{BatchKernel::Best, BatchKernel::Lanes2};
#if defined(__x86_64__)
    kernels.insert(kernels.end(), {BatchKernel::Lanes4Avx2, BatchKernel::Lanes8Avx512});
#endif
    std::vector<Case> cases;
    for (DistortionModel model : {DistortionModel::None, DistortionModel::RadialTangential, DistortionModel::Rational,
                                  DistortionModel::Fisheye})
        for (BatchKernel kernel : kernels)
            cases.push_back({model, kernel});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(ModelsAndKernels, BatchProjection, ::testing::ValuesIn(allCases()), [](const auto &param) {
    return std::string(test::modelName(param.param.model)) + "_" + kernelName(param.param.kernel);
});

} // namespace
} // namespace overlayd
