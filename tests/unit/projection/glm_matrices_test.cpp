// SPDX-License-Identifier: Apache-2.0
// glm_matrices_test: our view and projection matrices equal GLM's explicitly suffixed (RH_NO / RH_ZO) builders.
#include <algorithm>
#include <cmath>
#include <random>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "projection/pose.h"
#include "projection/projection.h"

using namespace overlayd;

namespace {

double maxAbs(const glm::dmat4 &m)
{
    double worst = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            worst = std::max(worst, std::abs(m[c][r]));
    return worst;
}

// Element-wise comparison, relative to the reference's largest entry once that exceeds 1: translations grow with
// the eye's distance and far/near ratios make depth entries large, and absolute 1e-12 would then test rounding.
::testing::AssertionResult matricesNear(const glm::dmat4 &actual, const glm::dmat4 &expected, double tolerance)
{
    const double scale = std::max(1.0, maxAbs(expected));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!(std::abs(actual[c][r] - expected[c][r]) <= tolerance * scale))
                return ::testing::AssertionFailure()
                       << "m[" << c << "][" << r << "] = " << actual[c][r] << ", expected " << expected[c][r]
                       << " (tolerance " << tolerance * scale << ")";
    return ::testing::AssertionSuccess();
}

constexpr double kTolerance = 1e-12;
constexpr int kTrials = 200;

class GlmMatrices : public ::testing::Test
{
protected:
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    // Spread near and far over several decades, the way real cameras use them.
    double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
    glm::dvec3 vec(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }

    std::mt19937_64 rng_{20240611};
};

TEST_F(GlmMatrices, LookAtViewMatrixEqualsLookAtRH)
{
    for (int i = 0; i < kTrials; ++i) {
        const glm::dvec3 eye = vec(-100.0, 100.0);
        const glm::dvec3 target = eye + vec(-10.0, 10.0);
        glm::dvec3 up = vec(-1.0, 1.0);
        // Keep clear of the degenerate up-parallel-to-gaze case, which bad_input_test covers.
        const double sine = glm::length(glm::cross(glm::normalize(up), glm::normalize(target - eye)));
        if (sine < 0.1 || glm::length(up) < 0.1)
            continue;
        auto pose = poseLookAt(eye, target, up);
        ASSERT_TRUE(pose.ok()) << pose.error().message;
        EXPECT_TRUE(matricesNear(pose->viewMatrix(), glm::lookAtRH(eye, target, up), kTolerance)) << "trial " << i;
    }
}

TEST_F(GlmMatrices, PerspectiveVerticalFovEqualsPerspectiveRH)
{
    for (int i = 0; i < kTrials; ++i) {
        const double fovy = uniform(1.0, 170.0);
        const double aspect = uniform(0.2, 5.0);
        const double near = logUniform(1e-3, 10.0);
        const double far = near * logUniform(1.5, 1e5);
        auto no = Projection::perspective(FovAxis::Vertical, fovy, aspect, near, far, DepthRange::MinusOneToOne);
        auto zo = Projection::perspective(FovAxis::Vertical, fovy, aspect, near, far, DepthRange::ZeroToOne);
        ASSERT_TRUE(no.ok() && zo.ok());
        EXPECT_TRUE(
            matricesNear(no->matrix(), glm::perspectiveRH_NO(glm::radians(fovy), aspect, near, far), kTolerance))
            << "trial " << i;
        EXPECT_TRUE(
            matricesNear(zo->matrix(), glm::perspectiveRH_ZO(glm::radians(fovy), aspect, near, far), kTolerance))
            << "trial " << i;
    }
}

TEST_F(GlmMatrices, PerspectiveHorizontalFovEqualsPerspectiveRHOfConvertedFov)
{
    for (int i = 0; i < kTrials; ++i) {
        const double fovx = uniform(1.0, 170.0);
        const double aspect = uniform(0.2, 5.0);
        const double near = logUniform(1e-3, 10.0);
        const double far = near * logUniform(1.5, 1e5);
        // The window is aspect times wider than tall: tan(fovy / 2) = tan(fovx / 2) / aspect.
        const double fovy = 2.0 * std::atan(std::tan(glm::radians(fovx) / 2.0) / aspect);
        auto no = Projection::perspective(FovAxis::Horizontal, fovx, aspect, near, far, DepthRange::MinusOneToOne);
        auto zo = Projection::perspective(FovAxis::Horizontal, fovx, aspect, near, far, DepthRange::ZeroToOne);
        ASSERT_TRUE(no.ok() && zo.ok());
        EXPECT_TRUE(matricesNear(no->matrix(), glm::perspectiveRH_NO(fovy, aspect, near, far), kTolerance))
            << "trial " << i;
        EXPECT_TRUE(matricesNear(zo->matrix(), glm::perspectiveRH_ZO(fovy, aspect, near, far), kTolerance))
            << "trial " << i;
    }
}

TEST_F(GlmMatrices, FrustumEqualsFrustumRH)
{
    for (int i = 0; i < kTrials; ++i) {
        const double near = logUniform(1e-3, 10.0);
        const double far = near * logUniform(1.5, 1e5);
        // Off-axis windows included: the optical axis need not pass through the window.
        const double left = uniform(-2.0, 1.0) * near;
        const double right = left + uniform(0.05, 3.0) * near;
        const double bottom = uniform(-2.0, 1.0) * near;
        const double top = bottom + uniform(0.05, 3.0) * near;
        const FrustumBounds bounds{left, right, bottom, top, near, far};
        auto no = Projection::frustum(bounds, DepthRange::MinusOneToOne);
        auto zo = Projection::frustum(bounds, DepthRange::ZeroToOne);
        ASSERT_TRUE(no.ok() && zo.ok());
        EXPECT_TRUE(matricesNear(no->matrix(), glm::frustumRH_NO(left, right, bottom, top, near, far), kTolerance))
            << "trial " << i;
        EXPECT_TRUE(matricesNear(zo->matrix(), glm::frustumRH_ZO(left, right, bottom, top, near, far), kTolerance))
            << "trial " << i;
    }
}

TEST_F(GlmMatrices, OrthographicEqualsOrthoRH)
{
    for (int i = 0; i < kTrials; ++i) {
        const double left = uniform(-50.0, 20.0);
        const double right = left + uniform(0.1, 60.0);
        const double bottom = uniform(-50.0, 20.0);
        const double top = bottom + uniform(0.1, 60.0);
        // A parallel box may start behind the camera.
        const double near = uniform(-20.0, 20.0);
        const double far = near + uniform(0.1, 500.0);
        const FrustumBounds bounds{left, right, bottom, top, near, far};
        auto no = Projection::orthographic(bounds, DepthRange::MinusOneToOne);
        auto zo = Projection::orthographic(bounds, DepthRange::ZeroToOne);
        ASSERT_TRUE(no.ok() && zo.ok());
        EXPECT_TRUE(matricesNear(no->matrix(), glm::orthoRH_NO(left, right, bottom, top, near, far), kTolerance))
            << "trial " << i;
        EXPECT_TRUE(matricesNear(zo->matrix(), glm::orthoRH_ZO(left, right, bottom, top, near, far), kTolerance))
            << "trial " << i;
        EXPECT_FALSE(no->isPerspective());
    }
}

TEST_F(GlmMatrices, InfiniteFarMinusOneToOneEqualsInfinitePerspectiveRH)
{
    for (int i = 0; i < kTrials; ++i) {
        const double fovy = uniform(1.0, 170.0);
        const double aspect = uniform(0.2, 5.0);
        const double near = logUniform(1e-3, 10.0);
        const glm::dmat4 expected = glm::infinitePerspectiveRH(glm::radians(fovy), aspect, near);

        auto fov =
            Projection::perspective(FovAxis::Vertical, fovy, aspect, near, kInfiniteFar, DepthRange::MinusOneToOne);
        ASSERT_TRUE(fov.ok());
        EXPECT_TRUE(matricesNear(fov->matrix(), expected, kTolerance)) << "trial " << i;
        EXPECT_FALSE(fov->hasFarPlane());

        // The same symmetric frustum given by its bounds on the near plane.
        const double top = near * std::tan(glm::radians(fovy) / 2.0);
        auto bounds = Projection::frustum({-top * aspect, top * aspect, -top, top, near, kInfiniteFar},
                                          DepthRange::MinusOneToOne);
        ASSERT_TRUE(bounds.ok());
        EXPECT_TRUE(matricesNear(bounds->matrix(), expected, kTolerance)) << "trial " << i;
    }
}

// GLM 0.9.9.8 has no infinitePerspectiveRH_ZO, so the ZeroToOne infinite-far matrix is checked against the limit of
// glm::perspectiveRH_ZO as far grows: the difference must shrink like near / far and be below 1e-12 once
// far / near = 1e15.
TEST_F(GlmMatrices, InfiniteFarZeroToOneIsTheLimitOfPerspectiveRHZO)
{
    for (int i = 0; i < kTrials / 4; ++i) {
        const double fovy = uniform(1.0, 170.0);
        const double aspect = uniform(0.2, 5.0);
        const double near = logUniform(1e-3, 10.0);
        auto infinite =
            Projection::perspective(FovAxis::Vertical, fovy, aspect, near, kInfiniteFar, DepthRange::ZeroToOne);
        ASSERT_TRUE(infinite.ok());
        for (int decade = 3; decade <= 15; ++decade) {
            const double ratio = std::pow(10.0, decade);
            const glm::dmat4 finite = glm::perspectiveRH_ZO(glm::radians(fovy), aspect, near, near * ratio);
            EXPECT_TRUE(matricesNear(infinite->matrix(), finite, 2.0 / ratio + kTolerance))
                << "trial " << i << ", far / near = " << ratio;
        }
        EXPECT_TRUE(matricesNear(infinite->matrix(),
                                 glm::perspectiveRH_ZO(glm::radians(fovy), aspect, near, near * 1e15), kTolerance))
            << "trial " << i;
    }
}

} // namespace
