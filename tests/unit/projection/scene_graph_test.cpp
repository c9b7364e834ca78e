// SPDX-License-Identifier: Apache-2.0
// scene_graph_test: world matrices compose along the path, cameras ride on frames, normals stay perpendicular.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "projection/camera.h"
#include "projection/pose.h"
#include "projection/projection.h"
#include "projection/scene_graph.h"
#include "projection/viewport.h"

using namespace overlayd;

namespace {

void expectVec(const glm::dvec3 &actual, const glm::dvec3 &expected, double tolerance, const char *what)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

template<typename T>
void expectError(const Result<T> &result, ErrorCode code)
{
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, code) << errorCodeName(result.error().code) << ": " << result.error().message;
    EXPECT_FALSE(result.error().message.empty());
}

// A robot: base on the ground, a mast on the base, a stretched pan head on the mast, a camera bracket on the head.
std::vector<FrameSpec> robot()
{
    return {
        {"base", "world", {{4.0, -2.0, 0.0}, glm::angleAxis(0.7, glm::dvec3(0, 0, 1)), {1.0, 1.0, 1.0}}},
        {"mast", "base", {{0.5, 0.0, 1.2}, glm::angleAxis(-0.3, glm::normalize(glm::dvec3(1, 2, 0))), {2.0, 2.0, 2.0}}},
        {"head", "mast", {{0.0, 0.1, 0.8}, glm::angleAxis(1.1, glm::normalize(glm::dvec3(0, 1, 1))), {1.0, 3.0, 0.2}}},
        {"bracket", "head", {{0.2, 0.0, 0.0}, glm::angleAxis(-2.0, glm::dvec3(1, 0, 0)), {0.5, 0.5, 0.5}}},
    };
}

// x_parent = t + q (s * x_local), applied point by point with GLM's quaternion rotation (no matrices involved).
glm::dvec3 toParent(const FrameSpec &frame, const glm::dvec3 &local)
{
    const Transform &t = frame.transform;
    return t.translation + t.rotation * (t.scale * local);
}

glm::dvec3 toWorldByHand(const std::vector<FrameSpec> &frames, const std::string &name, glm::dvec3 point)
{
    std::string current = name;
    while (current != SceneGraph::kWorld) {
        const auto it =
            std::find_if(frames.begin(), frames.end(), [&](const FrameSpec &f) { return f.name == current; });
        point = toParent(*it, point);
        current = it->parent;
    }
    return point;
}

TEST(SceneGraph, WorldMatricesComposeAlongThePath)
{
    const std::vector<FrameSpec> frames = robot();
    auto graph = SceneGraph::create(frames);
    ASSERT_TRUE(graph.ok()) << graph.error().message;
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (const FrameSpec &frame : frames) {
        auto world = graph->worldMatrix(frame.name);
        ASSERT_TRUE(world.ok());
        for (int i = 0; i < 20; ++i) {
            const glm::dvec3 local{u(rng), u(rng), u(rng)};
            const glm::dvec4 mapped = *world * glm::dvec4(local, 1.0);
            EXPECT_EQ(mapped.w, 1.0);
            expectVec(glm::dvec3(mapped), toWorldByHand(frames, frame.name, local), 1e-12, frame.name.c_str());
        }
    }
    auto world = graph->worldMatrix("world");
    ASSERT_TRUE(world.ok());
    EXPECT_EQ(*world, glm::dmat4(1.0));
    EXPECT_TRUE(graph->contains("world"));
    EXPECT_TRUE(graph->contains("bracket"));
    EXPECT_FALSE(graph->contains("Bracket"));
}

TEST(SceneGraph, FramesMayBeListedInAnyOrder)
{
    const std::vector<FrameSpec> ordered = robot();
    auto reference = SceneGraph::create(ordered);
    ASSERT_TRUE(reference.ok());
    std::vector<int> order{0, 1, 2, 3};
    do {
        std::vector<FrameSpec> shuffled;
        for (int i : order)
            shuffled.push_back(ordered[i]);
        auto graph = SceneGraph::create(shuffled);
        ASSERT_TRUE(graph.ok()) << graph.error().message;
        for (const FrameSpec &frame : ordered)
            EXPECT_EQ(*graph->worldMatrix(frame.name), *reference->worldMatrix(frame.name)) << frame.name;
    } while (std::next_permutation(order.begin(), order.end()));
}

TEST(SceneGraph, CameraAttachedToAFrame)
{
    auto graph = SceneGraph::create(robot());
    ASSERT_TRUE(graph.ok());
    // The camera sits at the bracket's origin looking along the bracket's +x axis, bracket +z up.
    auto mount = poseLookAt({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
    ASSERT_TRUE(mount.ok());
    const glm::dmat4 bracket = *graph->worldMatrix("bracket");
    const glm::dmat4 view = mount->viewMatrix() * glm::inverse(bracket);

    auto projection = Projection::perspective(FovAxis::Vertical, 60.0, 4.0 / 3.0, 0.01, 100.0, DepthRange::ZeroToOne);
    auto viewport = Viewport::create({640, 480});
    ASSERT_TRUE(projection.ok() && viewport.ok());
    auto camera = Camera::create(view, *projection, Distortion{}, *viewport);
    ASSERT_TRUE(camera.ok()) << camera.error().message;

    const std::vector<FrameSpec> frames = robot();
    expectVec(camera->position(), toWorldByHand(frames, "bracket", {0, 0, 0}), 1e-12, "camera centre");
    // A point ahead on the bracket's x axis is at the image centre; one on its +z axis is above the centre.
    const ProjectedPoint ahead = camera->project(toWorldByHand(frames, "bracket", {3, 0, 0}));
    ASSERT_EQ(ahead.status, PointStatus::Visible);
    EXPECT_NEAR(ahead.pixel.x, 319.5, 1e-9);
    EXPECT_NEAR(ahead.pixel.y, 239.5, 1e-9);
    const ProjectedPoint above = camera->project(toWorldByHand(frames, "bracket", {3, 0, 0.2}));
    ASSERT_EQ(above.status, PointStatus::Visible);
    EXPECT_NEAR(above.pixel.x, 319.5, 1e-9);
    EXPECT_LT(above.pixel.y, 239.5);
    // Bracket +y is the camera's left.
    const ProjectedPoint left = camera->project(toWorldByHand(frames, "bracket", {3, 0.2, 0}));
    EXPECT_LT(left.pixel.x, 319.5);
    EXPECT_NEAR(left.pixel.y, 239.5, 1e-9);
}

TEST(SceneGraph, NormalsStayPerpendicularUnderNonUniformScale)
{
    auto graph = SceneGraph::create(robot());
    ASSERT_TRUE(graph.ok());
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const char *name : {"head", "bracket", "mast"}) {
        const glm::dmat3 linear(*graph->worldMatrix(name));
        auto normals = graph->normalMatrix(name);
        ASSERT_TRUE(normals.ok());
        bool naiveFailed = false;
        for (int i = 0; i < 50; ++i) {
            // A surface patch with two tangents and their normal, in the frame's local coordinates.
            const glm::dvec3 t1{u(rng), u(rng), u(rng)}, t2{u(rng), u(rng), u(rng)};
            const glm::dvec3 n = glm::cross(t1, t2);
            if (glm::length(n) < 0.1)
                continue;
            const glm::dvec3 worldT1 = linear * t1, worldT2 = linear * t2;
            const glm::dvec3 worldN = glm::normalize(*normals * n);
            EXPECT_NEAR(glm::dot(worldN, glm::normalize(worldT1)), 0.0, 1e-12) << name;
            EXPECT_NEAR(glm::dot(worldN, glm::normalize(worldT2)), 0.0, 1e-12) << name;
            // It points to the same side as the transformed surface's own normal.
            EXPECT_GT(glm::dot(worldN, glm::cross(worldT1, worldT2)), 0.0) << name;
            // Transforming the normal like a point direction would not do (the reason for the normal matrix).
            naiveFailed |= std::abs(glm::dot(glm::normalize(linear * n), glm::normalize(worldT1))) > 1e-3;
        }
        // Only uniform scales lie on the mast's path, where the naive way happens to work.
        if (std::string(name) != "mast") {
            EXPECT_TRUE(naiveFailed) << name;
        }
    }
}

TEST(SceneGraph, UnknownParentIsRefused)
{
    expectError(SceneGraph::create({{"arm", "shoulder", {}}}), ErrorCode::UnknownFrame);
    auto graph = SceneGraph::create(robot());
    ASSERT_TRUE(graph.ok());
    expectError(graph->worldMatrix("elbow"), ErrorCode::UnknownFrame);
    expectError(graph->normalMatrix("elbow"), ErrorCode::UnknownFrame);
}

TEST(SceneGraph, DuplicateFrameIsRefused)
{
    expectError(SceneGraph::create({{"a", "world", {}}, {"b", "a", {}}, {"a", "world", {}}}),
                ErrorCode::DuplicateFrame);
    expectError(SceneGraph::create({{"world", "world", {}}}), ErrorCode::DuplicateFrame);
}

TEST(SceneGraph, CycleIsRefused)
{
    expectError(SceneGraph::create({{"a", "b", {}}, {"b", "a", {}}}), ErrorCode::CyclicFrames);
    expectError(SceneGraph::create({{"self", "self", {}}}), ErrorCode::CyclicFrames);
    // A frame hanging below a cycle is refused too, whatever the order.
    expectError(SceneGraph::create({{"leaf", "a", {}}, {"a", "b", {}}, {"b", "c", {}}, {"c", "a", {}}}),
                ErrorCode::CyclicFrames);
    expectError(SceneGraph::create({{"a", "b", {}}, {"b", "c", {}}, {"c", "a", {}}, {"leaf", "a", {}}}),
                ErrorCode::CyclicFrames);
}

TEST(SceneGraph, BadTransformsAreRefused)
{
    FrameSpec zeroScale{"flat", "world", {}};
    zeroScale.transform.scale = {1.0, 0.0, 1.0};
    expectError(SceneGraph::create({zeroScale}), ErrorCode::InvalidArgument);

    FrameSpec longQuaternion{"q", "world", {}};
    longQuaternion.transform.rotation = glm::dquat(1.0, 0.5, 0.0, 0.0);
    expectError(SceneGraph::create({longQuaternion}), ErrorCode::NotOrthonormal);
    FrameSpec zeroQuaternion{"q", "world", {}};
    zeroQuaternion.transform.rotation = glm::dquat(0.0, 0.0, 0.0, 0.0);
    expectError(SceneGraph::create({zeroQuaternion}), ErrorCode::NotOrthonormal);

    FrameSpec nanTranslation{"n", "world", {}};
    nanTranslation.transform.translation.y = std::nan("");
    expectError(SceneGraph::create({nanTranslation}), ErrorCode::InvalidArgument);
    FrameSpec infScale{"n", "world", {}};
    infScale.transform.scale.z = INFINITY;
    expectError(SceneGraph::create({infScale}), ErrorCode::InvalidArgument);

    expectError(SceneGraph::create({{"", "world", {}}}), ErrorCode::InvalidArgument);
}

} // namespace
