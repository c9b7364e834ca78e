// SPDX-License-Identifier: Apache-2.0
// clipping_test: nothing behind the near plane is drawn; segments and polygons are cut exactly at the planes.
//
// References: GLM (glm::lookAt, glm::perspectiveNO/ZO, glm::projectNO/ZO) for camera-space depths and pixels,
// OpenCV's projectPoints for the calibrated camera, and hand-worked clip-space answers for ClipPlanes.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_projection.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <opencv2/calib3d.hpp>

#include "projection/camera.h"
#include "projection/opencv_reference.h"

namespace overlayd {
namespace {

constexpr int kWidth = 640, kHeight = 480;
constexpr double kNear = 0.5, kFar = 100.0, kFovYDeg = 60.0;
const glm::dvec3 kEye(1.0, 2.0, 3.0), kTarget(-2.0, 1.5, -4.0), kUp(0.0, 1.0, 0.0);

// The reference pipeline, built from GLM only.
struct GlmCamera {
    DepthRange depth;
    glm::dmat4 view = glm::lookAt(kEye, kTarget, kUp);
    glm::dmat4 projection() const
    {
        const double aspect = double(kWidth) / kHeight;
        return depth == DepthRange::ZeroToOne ? glm::perspectiveZO(glm::radians(kFovYDeg), aspect, kNear, kFar)
                                              : glm::perspectiveNO(glm::radians(kFovYDeg), aspect, kNear, kFar);
    }
    // Distance in front of the camera along its viewing direction (negative behind it).
    double cameraDepth(const glm::dvec3 &p) const { return -(view * glm::dvec4(p, 1.0)).z; }
    glm::dvec4 clip(const glm::dvec3 &p) const { return projection() * view * glm::dvec4(p, 1.0); }
    // GLM's window coordinates have their origin at the bottom-left pixel corner; ours (top-left origin) are
    // pixel centres counted from the top: u = x - 0.5, v = H - y - 0.5.
    glm::dvec2 pixel(const glm::dvec3 &p) const
    {
        const glm::dvec4 viewport(0, 0, kWidth, kHeight);
        const glm::dvec3 w = depth == DepthRange::ZeroToOne ? glm::projectZO(p, view, projection(), viewport)
                                                            : glm::projectNO(p, view, projection(), viewport);
        return {w.x - 0.5, kHeight - w.y - 0.5};
    }
    // Top-left pixel back to NDC, independently of Viewport.
    static glm::dvec2 ndcOfPixel(const glm::dvec2 &px)
    {
        return {(px.x + 0.5) * 2.0 / kWidth - 1.0, 1.0 - (px.y + 0.5) * 2.0 / kHeight};
    }
};

Camera makeCamera(DepthRange depth)
{
    auto pose = poseLookAt(kEye, kTarget, kUp);
    auto projection =
        Projection::perspective(FovAxis::Vertical, kFovYDeg, double(kWidth) / kHeight, kNear, kFar, depth);
    auto viewport = Viewport::create({kWidth, kHeight});
    auto camera = Camera::create(*pose, *projection, Distortion{}, *viewport);
    EXPECT_TRUE(camera.ok());
    return std::move(camera).value();
}

// A world point at the given camera-space position (x right, y up, looking down -z), by GLM's inverse view.
glm::dvec3 worldFromCameraSpace(const GlmCamera &g, const glm::dvec3 &c)
{
    return glm::dvec3(glm::inverse(g.view) * glm::dvec4(c, 1.0));
}

glm::dvec3 randomInBox(std::mt19937_64 &rng, double half)
{
    std::uniform_real_distribution<double> u(-half, half);
    return {kEye.x + u(rng), kEye.y + u(rng), kEye.z + u(rng)};
}

class Clipping : public ::testing::TestWithParam<DepthRange>
{};

// Points around the camera: behind the near plane (including behind the camera) or beyond far never get a pixel.
TEST_P(Clipping, PointsOutsideNearFarAreClipped)
{
    const GlmCamera g{GetParam()};
    const Camera camera = makeCamera(GetParam());
    std::mt19937_64 rng(7);
    int behind = 0, front = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 p = randomInBox(rng, i % 2 ? 3.0 : 150.0);
        const double depth = g.cameraDepth(p);
        const ProjectedPoint projected = camera.project(p);
        if (depth < kNear * (1 - 1e-12) || depth > kFar * (1 + 1e-12)) {
            EXPECT_EQ(projected.status, PointStatus::Clipped) << "depth " << depth;
            behind += depth < kNear;
        } else if (depth > kNear * (1 + 1e-12) && depth < kFar * (1 - 1e-12)) {
            ASSERT_NE(projected.status, PointStatus::Clipped) << "depth " << depth;
            EXPECT_LE(glm::length(projected.pixel - g.pixel(p)), 1e-6);
            ++front;
        }
    }
    EXPECT_GT(behind, 5000);
    EXPECT_GT(front, 1000);
}

// What the textbook pipelines do with a point behind the camera: GLM's project() divides by a negative w and
// returns the pixel of the point mirrored through the camera centre. We return Clipped instead.
TEST_P(Clipping, GlmMirrorsPointsBehindTheCameraWeClipThem)
{
    const GlmCamera g{GetParam()};
    const Camera camera = makeCamera(GetParam());
    const glm::dvec3 behind = worldFromCameraSpace(g, {0.3, -0.2, 4.0}); // z > 0: behind the camera
    ASSERT_LT(g.cameraDepth(behind), 0.0);
    const glm::dvec3 mirrored = 2.0 * kEye - behind; // in front, inside the view
    ASSERT_GT(g.cameraDepth(mirrored), kNear);

    const glm::dvec2 glmBehind = g.pixel(behind);
    ASSERT_TRUE(std::isfinite(glmBehind.x) && std::isfinite(glmBehind.y));
    EXPECT_LE(glm::length(glmBehind - g.pixel(mirrored)), 1e-9)
        << "GLM is expected to produce the mirrored point's pixel for a point behind the camera";
    EXPECT_TRUE(glmBehind.x > 0 && glmBehind.x < kWidth && glmBehind.y > 0 && glmBehind.y < kHeight)
        << "the mirrored pixel lands inside the image, where a naive renderer would draw it";

    EXPECT_EQ(camera.project(behind).status, PointStatus::Clipped);
    EXPECT_NE(camera.project(mirrored).status, PointStatus::Clipped);
}

TEST(ClippingOpenCv, ProjectPointsMirrorsPointsBehindTheCameraWeClipThem)
{
    test::CvCamera c;
    c.rvec = {0.1, -0.4, 0.2};
    c.tvec = {0.5, 0.2, 1.0};
    c.fx = c.fy = 500;
    c.cx = 319.5;
    c.cy = 239.5;
    c.width = 640;
    c.height = 480;
    const Camera camera = test::makeCamera(c, DepthRange::ZeroToOne);
    const glm::dvec3 behind = test::worldFromOptical(c, {0.4, -0.3, -2.0}); // optical z < 0: behind
    const glm::dvec3 mirrored = test::worldFromOptical(c, {-0.4, 0.3, 2.0});
    const glm::dvec2 cvBehind = test::cvProject(c, behind);
    ASSERT_TRUE(std::isfinite(cvBehind.x) && std::isfinite(cvBehind.y));
    EXPECT_LE(glm::length(cvBehind - test::cvProject(c, mirrored)), 1e-9)
        << "cv::projectPoints is expected to produce the mirrored point's pixel for a point behind the camera";
    EXPECT_EQ(camera.project(behind).status, PointStatus::Clipped);
    EXPECT_EQ(camera.project(mirrored).status, PointStatus::Visible);
}

// Where on segment a-b a pixel produced from it lies: the t with ndc(clip(a + t (b - a))) = ndc(pixel), solved in
// whichever of x, y is better conditioned. Clip coordinates are linear in t, so this is exact up to rounding.
double parameterOfPixel(const GlmCamera &g, const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec2 &pixel)
{
    const glm::dvec4 ca = g.clip(a), d = g.clip(b) - ca;
    const glm::dvec2 ndc = GlmCamera::ndcOfPixel(pixel);
    const double denomX = d.x - ndc.x * d.w, denomY = d.y - ndc.y * d.w;
    if (std::abs(denomX) >= std::abs(denomY))
        return (ndc.x * ca.w - ca.x) / denomX;
    return (ndc.y * ca.w - ca.y) / denomY;
}

// Random segments behind, crossing and in front: every output endpoint is the pixel of a point of the segment at
// depth >= near; segments wholly behind the near plane produce nothing.
TEST_P(Clipping, SegmentOutputComesOnlyFromPointsInFrontOfNear)
{
    const GlmCamera g{GetParam()};
    const Camera camera = makeCamera(GetParam());
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int drawn = 0, behindOnly = 0;
    for (int i = 0; i < 5000; ++i) {
        // Depths along the view direction: a third cross the near plane, a third have one end behind and the other
        // anywhere, a third lie wholly behind; every fifth is wholly in front.
        auto behindNear = [&] {
            return kNear - 15.0 * (u(rng) + 1.0);
        };
        auto inFront = [&] {
            return kNear + 30.0 * (u(rng) + 1.0);
        };
        double depthA = i % 3 == 0 ? inFront() : behindNear();
        double depthB = i % 3 == 1 ? 20.0 * u(rng) : behindNear();
        if (i % 5 == 0)
            depthA = inFront(), depthB = inFront();
        const glm::dvec3 a = worldFromCameraSpace(g, {20.0 * u(rng), 20.0 * u(rng), -depthA});
        const glm::dvec3 b = worldFromCameraSpace(g, {20.0 * u(rng), 20.0 * u(rng), -depthB});
        Polylines out;
        camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);
        const bool allBehind = g.cameraDepth(a) < kNear && g.cameraDepth(b) < kNear;
        if (allBehind) {
            EXPECT_EQ(out.points.size(), 0u) << "segment " << i << " lies behind the near plane";
            ++behindOnly;
            continue;
        }
        ASSERT_LE(out.size(), 1u);
        if (out.size() == 0)
            continue; // outside the side planes
        ASSERT_EQ(out[0].size(), 2u) << "a segment through an ideal lens is one straight piece";
        ++drawn;
        for (const glm::dvec2 &pixel : out[0]) {
            const double t = parameterOfPixel(g, a, b, pixel);
            ASSERT_GE(t, -1e-9);
            ASSERT_LE(t, 1.0 + 1e-9);
            const glm::dvec3 p = a + std::clamp(t, 0.0, 1.0) * (b - a);
            EXPECT_GE(g.cameraDepth(p), kNear * (1.0 - 1e-9)) << "segment " << i << " t " << t;
            EXPECT_LE(glm::length(g.pixel(p) - pixel), 1e-6 * std::max(1.0, glm::length(pixel)))
                << "segment " << i << ": output pixel is not the image of the segment point it should be";
        }
    }
    EXPECT_GT(drawn, 500);
    EXPECT_GT(behindOnly, 500);
}

// A segment from a visible point to a point behind the camera, through a known point C of the near plane inside
// the view: the output runs from A's pixel to C's pixel exactly.
TEST_P(Clipping, CrossingSegmentIsCutExactlyAtNear)
{
    const GlmCamera g{GetParam()};
    const Camera camera = makeCamera(GetParam());
    const double tanY = std::tan(glm::radians(kFovYDeg) / 2.0), tanX = tanY * kWidth / kHeight;
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-0.9, 0.9);
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 cCam(u(rng) * tanX * kNear, u(rng) * tanY * kNear, -kNear);
        const double depthA = kNear + 0.1 + 20.0 * (u(rng) + 0.9);
        const glm::dvec3 aCam(u(rng) * tanX * depthA, u(rng) * tanY * depthA, -depthA);
        const glm::dvec3 bCam = cCam + (cCam - aCam) * (0.2 + 3.0 * (u(rng) + 0.9)); // behind the near plane
        const glm::dvec3 a = worldFromCameraSpace(g, aCam), b = worldFromCameraSpace(g, bCam);
        const glm::dvec3 c = worldFromCameraSpace(g, cCam);
        Polylines out;
        camera.projectSegment(glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), out);
        ASSERT_EQ(out.size(), 1u) << "segment " << i;
        ASSERT_EQ(out[0].size(), 2u);
        EXPECT_LE(glm::length(out[0][0] - g.pixel(a)), 1e-6) << "segment " << i;
        EXPECT_LE(glm::length(out[0][1] - g.pixel(c)), 1e-6) << "segment " << i << " is not cut at the near plane";
        const double t = parameterOfPixel(g, a, b, out[0][1]);
        EXPECT_NEAR(g.cameraDepth(a + t * (b - a)), kNear, 1e-9 * kNear);

        // The same segment the other way round: cut at the same point.
        Polylines reversed;
        camera.projectSegment(glm::dvec4(b, 1.0), glm::dvec4(a, 1.0), reversed);
        ASSERT_EQ(reversed.size(), 1u);
        EXPECT_LE(glm::length(reversed[0][0] - g.pixel(c)), 1e-6);
        EXPECT_LE(glm::length(reversed[0][1] - g.pixel(a)), 1e-6);
    }
}

INSTANTIATE_TEST_SUITE_P(Depth, Clipping, ::testing::Values(DepthRange::MinusOneToOne, DepthRange::ZeroToOne),
                         [](const auto &param) {
                             return std::string(param.param == DepthRange::ZeroToOne ? "ZeroToOne" : "MinusOneToOne");
                         });

// ClipPlanes on hand-worked clip-space inputs. Near is z >= 0 (ZeroToOne) or z >= -w (MinusOneToOne), far is
// z <= w, sides |x|, |y| <= w for the default bounds.
struct SegmentCase {
    glm::dvec4 a, b;
    std::optional<std::array<double, 2>> minusOneToOne, zeroToOne;
};

TEST(ClipPlanesAnalytic, ClipSegment)
{
    using Range = std::optional<std::array<double, 2>>;
    const SegmentCase cases[] = {
        // Along the axis from behind near to inside: near depth -w (NO) at t = 2/6, 0 (ZO) at t = 3/4.
        {{0, 0, -3, 1}, {0, 0, 1, 3}, Range({1.0 / 3.0, 1.0}), Range({0.75, 1.0})},
        // Reversed: the same cut from the other end.
        {{0, 0, 1, 3}, {0, 0, -3, 1}, Range({0.0, 2.0 / 3.0}), Range({0.0, 0.25})},
        // Through the far plane: w - z goes 0.5 -> -3, so t1 = 0.5 / 3.5.
        {{0, 0, 0.5, 1}, {0, 0, 5, 2}, Range({0.0, 1.0 / 7.0}), Range({0.0, 1.0 / 7.0})},
        // Through the right plane: w - x goes 1 -> -3, t1 = 1/4.
        {{0, 0, 0.5, 1}, {4, 0, 0.5, 1}, Range({0.0, 0.25}), Range({0.0, 0.25})},
        // Through the bottom plane from outside: y + w goes -1 -> 1, t0 = 1/2.
        {{0, -2, 0.5, 1}, {0, 0, 0.5, 1}, Range({0.5, 1.0}), Range({0.5, 1.0})},
        // Wholly behind the camera (w < 0, and behind near in both conventions).
        {{0, 0, -2, -1}, {0.5, 0.5, -3, -2}, std::nullopt, std::nullopt},
        // Between near planes: inside for MinusOneToOne (z >= -w), outside for ZeroToOne (z < 0).
        {{0, 0, -0.5, 1}, {0.2, 0, -0.25, 1}, Range({0.0, 1.0}), std::nullopt},
        // Enters through the left plane (x + w: -2 -> 2) and leaves through the far plane (w - z: 1 -> -0.5).
        {{-3, 0, 0, 1}, {1, 0, 1.5, 1}, Range({0.5, 2.0 / 3.0}), Range({0.5, 2.0 / 3.0})},
    };
    for (const auto depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        const ClipPlanes planes(depth, true, NdcBounds{});
        for (std::size_t i = 0; i < std::size(cases); ++i) {
            const auto &k = cases[i];
            const Range want = depth == DepthRange::ZeroToOne ? k.zeroToOne : k.minusOneToOne;
            const Range got = planes.clipSegment(k.a, k.b);
            ASSERT_EQ(got.has_value(), want.has_value())
                << "case " << i << (want ? " should" : " should not") << " survive, depth " << static_cast<int>(depth);
            if (want) {
                EXPECT_NEAR((*got)[0], (*want)[0], 1e-15) << "case " << i;
                EXPECT_NEAR((*got)[1], (*want)[1], 1e-15) << "case " << i;
            }
        }
    }
}

TEST(ClipPlanesAnalytic, ClipSegmentWithoutFarPlaneKeepsFarPoints)
{
    const ClipPlanes planes(DepthRange::ZeroToOne, false, NdcBounds{});
    const auto range = planes.clipSegment({0, 0, 0.5, 1}, {0, 0, 5, 2});
    ASSERT_TRUE(range);
    EXPECT_EQ((*range)[0], 0.0);
    EXPECT_EQ((*range)[1], 1.0);
}

// Equal as cyclic sequences (Sutherland-Hodgman may start the output anywhere on the polygon).
void expectSameCycle(const std::vector<glm::dvec4> &got, const std::vector<glm::dvec4> &want)
{
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t shift = 0; shift < want.size(); ++shift) {
        bool same = true;
        for (std::size_t i = 0; i < want.size() && same; ++i)
            same = glm::length(got[(i + shift) % got.size()] - want[i]) < 1e-14;
        if (same)
            return;
    }
    std::string text;
    for (const glm::dvec4 &v : got)
        text += "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ", " +
                std::to_string(v.w) + ") ";
    ADD_FAILURE() << "clipped polygon differs from the expected one; got " << text;
}

TEST(ClipPlanesAnalytic, ClipPolygonStraddlingNear)
{
    // P0 behind the near plane in both conventions; P1, P2 inside every plane.
    const std::vector<glm::dvec4> triangle{{0, 0, -3, 1}, {0.5, 0, 1, 2}, {-0.5, 0.5, 1, 2}};
    std::vector<glm::dvec4> out;

    // MinusOneToOne: z + w is -2, 3, 3: edge P0P1 is cut at t = 2/5, edge P2P0 at t = 3/5.
    ClipPlanes(DepthRange::MinusOneToOne, true, NdcBounds{}).clipPolygon(triangle, out);
    expectSameCycle(out, {{0.2, 0, -1.4, 1.4}, {0.5, 0, 1, 2}, {-0.5, 0.5, 1, 2}, {-0.2, 0.2, -1.4, 1.4}});

    // ZeroToOne: z is -3, 1, 1: edge P0P1 is cut at t = 3/4, edge P2P0 at t = 1/4.
    ClipPlanes(DepthRange::ZeroToOne, true, NdcBounds{}).clipPolygon(triangle, out);
    expectSameCycle(out, {{0.375, 0, 0, 1.75}, {0.5, 0, 1, 2}, {-0.5, 0.5, 1, 2}, {-0.375, 0.375, 0, 1.75}});

    // Wholly behind: nothing; wholly inside: unchanged.
    const std::vector<glm::dvec4> behind{{0, 0, -3, 1}, {0.1, 0, -4, 1}, {0, 0.1, -5, 1}};
    ClipPlanes(DepthRange::ZeroToOne, true, NdcBounds{}).clipPolygon(behind, out);
    EXPECT_TRUE(out.empty());
    const std::vector<glm::dvec4> inside{{0, 0, 0.5, 1}, {0.5, 0, 0.5, 1}, {0, 0.5, 0.5, 1}};
    ClipPlanes(DepthRange::MinusOneToOne, true, NdcBounds{}).clipPolygon(inside, out);
    expectSameCycle(out, inside);
}

// Every vertex of a clipped random polygon is inside all planes (within rounding); a polygon crossing only the
// near plane keeps its area's part in front (checked through the vertices lying on the near plane).
TEST(ClipPlanesAnalytic, ClipPolygonOutputInsideAllPlanes)
{
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (const auto depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        const ClipPlanes planes(depth, true, NdcBounds{-1.5, 1.5, -1.2, 1.2});
        std::vector<glm::dvec4> out;
        for (int i = 0; i < 2000; ++i) {
            std::vector<glm::dvec4> polygon;
            for (int v = 0; v < 3 + i % 4; ++v)
                polygon.push_back({u(rng), u(rng), u(rng), u(rng)});
            planes.clipPolygon(polygon, out);
            for (const glm::dvec4 &v : out)
                for (const glm::dvec4 &plane : planes.planes())
                    EXPECT_GE(glm::dot(plane, v), -1e-12) << "polygon " << i;
        }
    }
}

// Infinite far (glFrustum with far -> infinity): directions (w = 0) in front of the camera project to their
// vanishing point at NDC depth 1; directions behind or sideways do not.
TEST(ClippingInfiniteFar, DirectionsInFrontProjectDirectionsBehindDoNot)
{
    const FrustumBounds bounds{-0.4, 0.3, -0.2, 0.25, 0.5, kInfiniteFar};
    for (const auto depth : {DepthRange::MinusOneToOne, DepthRange::ZeroToOne}) {
        auto projection = Projection::frustum(bounds, depth);
        ASSERT_TRUE(projection.ok());
        EXPECT_FALSE(projection->hasFarPlane());
        auto viewport = Viewport::create({kWidth, kHeight});
        // Identity view: camera space is world space.
        auto camera = Camera::create(glm::dmat4(1.0), *projection, Distortion{}, *viewport);
        ASSERT_TRUE(camera.ok());
        std::mt19937_64 rng(19);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 d(u(rng), u(rng), u(rng));
            const ProjectedPoint p = camera->project(glm::dvec4(d, 0.0));
            if (d.z >= 0.0) {
                EXPECT_EQ(p.status, PointStatus::Clipped) << "direction behind the camera";
                continue;
            }
            ASSERT_NE(p.status, PointStatus::Clipped);
            // glFrustum's definition: the direction meets the near plane at near * (x, y) / -z.
            const double xn = bounds.near * d.x / -d.z, yn = bounds.near * d.y / -d.z;
            const glm::dvec2 ndc(2.0 * (xn - bounds.left) / (bounds.right - bounds.left) - 1.0,
                                 2.0 * (yn - bounds.bottom) / (bounds.top - bounds.bottom) - 1.0);
            const glm::dvec2 want((ndc.x + 1.0) * kWidth / 2.0 - 0.5, (1.0 - ndc.y) * kHeight / 2.0 - 0.5);
            EXPECT_LE(glm::length(p.pixel - want), 1e-9 * std::max(1.0, glm::length(want)));
            EXPECT_NEAR(p.depth, 1.0, 1e-15) << "points at infinity lie on the far plane at infinity";
            // A finite point very far along the direction still projects (no far plane) to nearly the same pixel.
            const ProjectedPoint far = camera->project(glm::dvec3(d * 1e9));
            ASSERT_NE(far.status, PointStatus::Clipped);
            EXPECT_LE(glm::length(far.pixel - p.pixel), 1e-6 * std::max(1.0, glm::length(want)));
            EXPECT_LT(far.depth, 1.0);
        }

        // A ray from a visible point towards a direction in front is drawn up to its vanishing point.
        const glm::dvec4 start(0.05, 0.02, -2.0, 1.0), direction(0.1, 0.05, -1.0, 0.0);
        Polylines out;
        camera->projectSegment(start, direction, out);
        ASSERT_EQ(out.size(), 1u);
        EXPECT_LE(glm::length(out[0][0] - camera->project(start).pixel), 1e-9);
        EXPECT_LE(glm::length(out[0][1] - camera->project(direction).pixel), 1e-9);
        // A direction pointing backwards gives nothing beyond the part of the segment in front.
        EXPECT_EQ(camera->project(glm::dvec4(0.1, 0.05, 1.0, 0.0)).status, PointStatus::Clipped);
    }
}

} // namespace
} // namespace overlayd
