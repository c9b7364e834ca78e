// SPDX-License-Identifier: Apache-2.0
// viewing_pipeline_test: the classic viewing pipeline's worked mappings (window, viewport, NDC) hold for our matrices.
#include <cmath>
#include <random>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/viewing_pipeline.h"
#include "projection/viewport.h"

using namespace overlayd;

namespace {

constexpr double kTolerance = 1e-12;

// A 4x4 matrix from its rows as the classic derivation prints them (GLM stores columns).
glm::dmat4 fromRows(const glm::dvec4 &r0, const glm::dvec4 &r1, const glm::dvec4 &r2, const glm::dvec4 &r3)
{
    return glm::transpose(glm::dmat4(r0, r1, r2, r3));
}

glm::dvec3 divide(const glm::dvec4 &h)
{
    return glm::dvec3(h) / h.w;
}

void expectVecNear(const glm::dvec3 &actual, const glm::dvec3 &expected, double tolerance, const char *what)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

void expectMatNear(const glm::dmat4 &actual, const glm::dmat4 &expected, double tolerance)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "m[" << c << "][" << r << "]";
}

// The viewing pipeline's example window: focal 2, centre CW offset (0.3, -0.2) from the optical axis, 1.6 x 0.9 wide.
constexpr double kFocal = 2.0, kWidth = 1.6, kHeight = 0.9, kNear = 0.5, kFar = 50.0;
const glm::dvec3 kCw{0.3, -0.2, -kFocal};

// --- The viewing pipeline, step by step
// ---------------------------------------------------------------------------------------

TEST(ViewingPipeline, ShearMovesTheWindowCentreOntoTheMinusZAxis)
{
    const glm::dmat4 h = ViewingPipeline::shear(kCw);
    expectVecNear(divide(h * glm::dvec4(kCw, 1.0)), {0.0, 0.0, -kFocal}, kTolerance, "H CW");
    // The seed's matrix as printed: third column -CW_x / CW_z, -CW_y / CW_z.
    expectMatNear(h, fromRows({1, 0, -kCw.x / kCw.z, 0}, {0, 1, -kCw.y / kCw.z, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}),
                  kTolerance);
    // A shear along z: depth is untouched and the plane z = 0 (the centre of projection) stays put.
    expectVecNear(divide(h * glm::dvec4(0.7, -0.4, 0.0, 1.0)), {0.7, -0.4, 0.0}, kTolerance, "H on z = 0");
    EXPECT_NEAR((h * glm::dvec4(0.7, -0.4, -3.0, 1.0)).z, -3.0, kTolerance);
}

TEST(ViewingPipeline, ScaleXYOpensTheWindowEdgesAt45Degrees)
{
    const glm::dmat4 sh = ViewingPipeline::scaleXY(kFocal, kWidth, kHeight) * ViewingPipeline::shear(kCw);
    for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
            const glm::dvec3 corner = kCw + glm::dvec3(sx * kWidth / 2.0, sy * kHeight / 2.0, 0.0);
            const glm::dvec3 p = divide(sh * glm::dvec4(corner, 1.0));
            // 45 degrees: |x| = |y| = -z at every window corner.
            EXPECT_NEAR(p.x, sx * -p.z, kTolerance);
            EXPECT_NEAR(p.y, sy * -p.z, kTolerance);
            EXPECT_NEAR(p.z, -kFocal, kTolerance);
        }
    }
}

TEST(ViewingPipeline, ScaleFarPutsTheFarPlaneAtMinusOne)
{
    const glm::dmat4 s = ViewingPipeline::scaleFar(kFar);
    EXPECT_NEAR((s * glm::dvec4(3.0, -2.0, -kFar, 1.0)).z, -1.0, kTolerance);
    EXPECT_NEAR((s * glm::dvec4(3.0, -2.0, -kNear, 1.0)).z, -kNear / kFar, kTolerance);
    // Uniform: the 45-degree edges stay at 45 degrees.
    const glm::dvec4 edge = s * glm::dvec4(kFar, kFar, -kFar, 1.0);
    EXPECT_NEAR(edge.x, -edge.z, kTolerance);
    EXPECT_NEAR(edge.y, -edge.z, kTolerance);
}

TEST(ViewingPipeline, PerspectiveMapsNearToZeroAndFarToOne)
{
    const double n = kNear / kFar;
    const glm::dmat4 p = ViewingPipeline::perspective(n);
    EXPECT_NEAR(divide(p * glm::dvec4(0, 0, -n, 1)).z, 0.0, kTolerance);
    EXPECT_NEAR(divide(p * glm::dvec4(0, 0, -1, 1)).z, 1.0, kTolerance);
    // x' = x / -z and y' = y / -z: the 45-degree cone becomes the box [-1, 1]^2.
    const glm::dvec3 corner = divide(p * glm::dvec4(0.4, -0.4, -0.4, 1.0));
    EXPECT_NEAR(corner.x, 1.0, kTolerance);
    EXPECT_NEAR(corner.y, -1.0, kTolerance);
    // Depth grows monotonically with distance between the planes.
    double previous = -1.0;
    for (double z = n; z <= 1.0; z += 0.01) {
        const double depth = divide(p * glm::dvec4(0, 0, -z, 1)).z;
        EXPECT_GT(depth, previous);
        previous = depth;
    }

    // The derivation prints the third row as (0, 0, 1/(1-n), n/(1-n)) and claims the box [0, 1]; that row sends near to
    // 0 but far to -1 (its own z' = -(z + n) / (z (1 - n)) gives -1 at z = -1). We use the negated row.
    const glm::dmat4 printed = fromRows({1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1 / (1 - n), n / (1 - n)}, {0, 0, -1, 0});
    EXPECT_NEAR(divide(printed * glm::dvec4(0, 0, -n, 1)).z, 0.0, kTolerance);
    EXPECT_NEAR(divide(printed * glm::dvec4(0, 0, -1, 1)).z, -1.0, kTolerance);
}

TEST(ViewingPipeline, NormalizeMapsTheSquareToTheUnitSquare)
{
    const glm::dmat4 n = ViewingPipeline::normalize();
    expectVecNear(divide(n * glm::dvec4(-1, -1, 0.25, 1)), {0.0, 0.0, 0.25}, kTolerance, "N(-1, -1)");
    expectVecNear(divide(n * glm::dvec4(1, 1, 0.75, 1)), {1.0, 1.0, 0.75}, kTolerance, "N(1, 1)");
    expectVecNear(divide(n * glm::dvec4(0, 0, 0, 1)), {0.5, 0.5, 0.0}, kTolerance, "N(0, 0)");
}

TEST(ViewingPipeline, ParallelDropsOrKeepsDepth)
{
    const glm::dvec4 p(0.2, -0.3, 0.6, 1.0);
    EXPECT_EQ((ViewingPipeline::parallel(false) * p).z, 0.0);
    EXPECT_EQ((ViewingPipeline::parallel(true) * p).z, 0.6);
    EXPECT_EQ((ViewingPipeline::parallel(false) * p).x, 0.2);
}

// T_camera = T_raster S_raster N P_parallel P_persp S_far S_xy H R T: the derivation's corner-based raster coordinates
// with a bottom-left origin are our pixel centres + 0.5.
TEST(ViewingPipeline, FullChainEqualsCameraPixelsPlusHalf)
{
    const glm::dvec3 prp{4.0, -3.0, 2.0};
    const glm::dvec3 vpn{0.8, -0.5, 0.4}; // towards the viewer
    const glm::dvec3 vup{0.0, 0.0, 1.0};
    const int frameWidth = 1280, frameHeight = 720;
    const int posx = 200, posy = 100, xres = 800, yres = 450; // xres / yres = kWidth / kHeight: square pixels

    auto pose = poseFromPrpVpnVup(prp, vpn, vup);
    ASSERT_TRUE(pose.ok());
    // R T written out from the seed: rows X', Y', Z' times the translation by -PRP.
    const glm::dvec3 zAxis = glm::normalize(vpn);
    const glm::dvec3 xAxis = glm::normalize(glm::cross(vup, zAxis));
    const glm::dvec3 yAxis = glm::cross(zAxis, xAxis);
    const glm::dmat4 r = glm::transpose(
        glm::dmat4(glm::dvec4(xAxis, 0.0), glm::dvec4(yAxis, 0.0), glm::dvec4(zAxis, 0.0), glm::dvec4(0, 0, 0, 1)));
    glm::dmat4 t(1.0);
    t[3] = glm::dvec4(-prp, 1.0);

    const glm::dmat4 chain = ViewingPipeline::rasterTranslate(posx, posy) * ViewingPipeline::rasterScale(xres, yres) *
                             ViewingPipeline::normalize() * ViewingPipeline::parallel(true) *
                             ViewingPipeline::perspective(kNear / kFar) * ViewingPipeline::scaleFar(kFar) *
                             ViewingPipeline::scaleXY(kFocal, kWidth, kHeight) * ViewingPipeline::shear(kCw) * r * t;

    auto projection =
        Projection::window({kFocal, {kCw.x, kCw.y}, kWidth / 2.0, kHeight / 2.0, kNear, kFar}, DepthRange::ZeroToOne);
    ASSERT_TRUE(projection.ok());
    ViewportSpec spec{frameWidth, frameHeight, PixelRect{posx, posy, xres, yres}, Origin::BottomLeft};
    auto viewport = Viewport::create(spec);
    ASSERT_TRUE(viewport.ok());
    auto camera = Camera::create(*pose, *projection, Distortion{}, *viewport);
    ASSERT_TRUE(camera.ok());

    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> spread(-1.0, 1.0), distance(1.0, 40.0);
    for (int i = 0; i < 200; ++i) {
        // Points in front of the camera (along -VPN), spread over and beyond the window.
        const double d = distance(rng);
        const glm::dvec3 world = prp - d * zAxis + d * spread(rng) * xAxis + d * spread(rng) * yAxis;
        const glm::dvec3 raster = divide(chain * glm::dvec4(world, 1.0));
        const ProjectedPoint p = camera->project(world);
        ASSERT_NE(p.status, PointStatus::Clipped);
        // The camera answers in memory order; the seed counts rows from the bottom, as the user's origin does.
        const glm::dvec2 pixel = camera->viewport().toUser(p.pixel);
        EXPECT_NEAR(pixel.x + 0.5, raster.x, 1e-9) << "point " << i;
        EXPECT_NEAR(pixel.y + 0.5, raster.y, 1e-9) << "point " << i;
        EXPECT_NEAR(p.depth, raster.z, 1e-12) << "point " << i;
    }
}

TEST(SeedMappings, WindowOrthographicEqualsOrthoRHZOForACentredWindow)
{
    const double width = 4.0, height = 3.0, near = 0.5, far = 30.0;
    expectMatNear(ViewingPipeline::orthographic(width, height, near, far),
                  glm::orthoRH_ZO(-width / 2, width / 2, -height / 2, height / 2, near, far), kTolerance);
    auto projection = Projection::windowOrthographic(width, height, near, far, DepthRange::MinusOneToOne);
    ASSERT_TRUE(projection.ok());
    expectMatNear(projection->matrix(), glm::orthoRH_NO(-width / 2, width / 2, -height / 2, height / 2, near, far),
                  kTolerance);

    // The seed's printed S_xyz has +1/(far - near) and sends the far plane to -1, its box "[0 .. -1]".
    glm::dmat4 printedScale(1.0);
    printedScale[0][0] = 2 / width;
    printedScale[1][1] = 2 / height;
    printedScale[2][2] = 1 / (far - near);
    const glm::dmat4 tNear = fromRows({1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, near}, {0, 0, 0, 1});
    EXPECT_NEAR((printedScale * tNear * glm::dvec4(0, 0, -far, 1)).z, -1.0, kTolerance);
    EXPECT_NEAR((printedScale * tNear * glm::dvec4(0, 0, -near, 1)).z, 0.0, kTolerance);
}

// --- The viewing pipeline: pseudodepth
// --------------------------------------------------------------------------------------

TEST(SeedMappings, Seed004PseudodepthMapsNearToMinusOneAndFarToOne)
{
    // The viewing pipeline looks along +z with the near plane at z = f and the far plane at z = F; z* = (f / p)(a p +
    // b) with a, b solved from z*(f) = -1, z*(F) = 1. Our camera looks down -z, so its point at depth p has z = -p.
    const double f = 0.25, bigF = 80.0;
    const double a = (bigF + f) / (f * (bigF - f));
    const double b = -2.0 * bigF / (bigF - f);
    const auto pseudodepth = [&](double p) {
        return f / p * (a * p + b);
    };
    EXPECT_NEAR(pseudodepth(f), -1.0, kTolerance);
    EXPECT_NEAR(pseudodepth(bigF), 1.0, kTolerance);

    auto projection = Projection::perspective(FovAxis::Vertical, 60.0, 1.5, f, bigF, DepthRange::MinusOneToOne);
    ASSERT_TRUE(projection.ok());
    for (double p = f; p <= bigF; p *= 1.3) {
        const glm::dvec4 clip = projection->matrix() * glm::dvec4(0.1, -0.2, -p, 1.0);
        EXPECT_NEAR(clip.z / clip.w, pseudodepth(p), 1e-12) << "depth " << p;
    }
    EXPECT_NEAR(ndcNearDepth(DepthRange::MinusOneToOne), -1.0, 0.0);
    EXPECT_NEAR(ndcNearDepth(DepthRange::ZeroToOne), 0.0, 0.0);
}

// --- The viewing pipeline
// ---------------------------------------------------------------------------------------------------

TEST(SeedMappings, Seed001ViewportMapsTheClipSquareOntoThePixelCorners)
{
    const int nx = 640, ny = 360;
    // M_vp as printed: x_screen = nx/2 x + nx/2, y_screen = ny/2 y + ny/2, in corner-based coordinates.
    const auto mvp = [&](const glm::dvec2 &ndc) {
        return glm::dvec2(nx / 2.0 * ndc.x + nx / 2.0, ny / 2.0 * ndc.y + ny / 2.0);
    };
    EXPECT_EQ(mvp({-1, -1}), glm::dvec2(0, 0));
    EXPECT_EQ(mvp({1, 1}), glm::dvec2(nx, ny));

    auto viewport = Viewport::create({nx, ny, std::nullopt, Origin::BottomLeft});
    ASSERT_TRUE(viewport.ok());
    EXPECT_EQ(viewport->ndcToPixel({-1, -1}) + 0.5, glm::dvec2(0, 0));
    EXPECT_EQ(viewport->ndcToPixel({1, 1}) + 0.5, glm::dvec2(nx, ny));
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> ndc(-1.5, 1.5);
    for (int i = 0; i < 100; ++i) {
        const glm::dvec2 q{ndc(rng), ndc(rng)};
        const glm::dvec2 pixel = viewport->ndcToPixel(q);
        EXPECT_NEAR(pixel.x + 0.5, mvp(q).x, 1e-12);
        EXPECT_NEAR(pixel.y + 0.5, mvp(q).y, 1e-12);
    }
}

TEST(SeedMappings, Seed001CameraFrameFromEyeGazeAndUp)
{
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> component(-5.0, 5.0);
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 e{component(rng), component(rng), component(rng)};
        const glm::dvec3 g{component(rng), component(rng), component(rng)};
        const glm::dvec3 up{component(rng), component(rng), component(rng)};
        if (glm::length(glm::cross(glm::normalize(g), glm::normalize(up))) < 0.1)
            continue;
        // w = -g / |g|, u = t x w / |t x w|, v = w x u.
        const glm::dvec3 w = -g / glm::length(g);
        const glm::dvec3 u = glm::cross(up, w) / glm::length(glm::cross(up, w));
        const glm::dvec3 v = glm::cross(w, u);
        auto pose = poseFromGaze(e, g, up);
        ASSERT_TRUE(pose.ok());
        // M_cam = [u v w e; 0 0 0 1]^-1.
        const glm::dmat4 mCam =
            glm::inverse(glm::dmat4(glm::dvec4(u, 0), glm::dvec4(v, 0), glm::dvec4(w, 0), glm::dvec4(e, 1)));
        expectMatNear(pose->viewMatrix(), mCam, 1e-12);
        expectVecNear(pose->position(), e, 1e-12, "position");
    }
}

TEST(SeedMappings, Seed001GluPerspectiveMatrixAsPrinted)
{
    const double fovy = 50.0, aspect = 16.0 / 9.0, zNear = 0.3, zFar = 120.0;
    const double f = 1.0 / std::tan(fovy * M_PI / 360.0); // cot(fovy / 2)
    const glm::dmat4 printed =
        fromRows({f / aspect, 0, 0, 0}, {0, f, 0, 0},
                 {0, 0, (zFar + zNear) / (zNear - zFar), 2 * zFar * zNear / (zNear - zFar)}, {0, 0, -1, 0});
    auto projection = Projection::perspective(FovAxis::Vertical, fovy, aspect, zNear, zFar, DepthRange::MinusOneToOne);
    ASSERT_TRUE(projection.ok());
    expectMatNear(projection->matrix(), printed, 1e-12);
}

TEST(SeedMappings, Seed001OrthographicBoxMapsOntoTheClipCube)
{
    // M_orth for [l,r] x [b,t] x [f,n] with n, f the (negative) z of the near and far faces.
    const double l = -3, r = 5, b = -1, t = 2, n = -0.5, f = -20;
    auto projection = Projection::orthographic({l, r, b, t, -n, -f}, DepthRange::MinusOneToOne);
    ASSERT_TRUE(projection.ok());
    expectVecNear(divide(projection->matrix() * glm::dvec4(l, b, f, 1)), {-1, -1, 1}, kTolerance, "(l, b, f)");
    expectVecNear(divide(projection->matrix() * glm::dvec4(r, t, n, 1)), {1, 1, -1}, kTolerance, "(r, t, n)");
    // The seed maps (l, b, f) to z = -1 and (r, t, n) to z = +1 (its M_orth row 2/(n - f), -(n + f)/(n - f));
    // glOrtho and we put near at -1 and far at +1, so only the depth sign differs from the printed matrix.
    const glm::dmat4 printed =
        fromRows({2 / (r - l), 0, 0, -(r + l) / (r - l)}, {0, 2 / (t - b), 0, -(t + b) / (t - b)},
                 {0, 0, 2 / (n - f), -(n + f) / (n - f)}, {0, 0, 0, 1});
    expectVecNear(divide(printed * glm::dvec4(l, b, f, 1)), {-1, -1, -1}, kTolerance, "printed (l, b, f)");
    glm::dmat4 flipDepth(1.0);
    flipDepth[2][2] = -1.0;
    expectMatNear(projection->matrix(), flipDepth * printed, kTolerance);
}

} // namespace
