// SPDX-License-Identifier: Apache-2.0
// Scene-graph resolution: validates the frames and composes world matrices along each path.
#include "scene_graph.h"

#include <cmath>
#include <set>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "checks.h"

namespace overlayd {

glm::dmat4 Transform::matrix() const
{
    glm::dmat4 m = glm::mat4_cast(glm::normalize(rotation));
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
}

namespace {

Status validateFrame(const FrameSpec &frame)
{
    const std::string where = "frame '" + frame.name + "': ";
    if (frame.name.empty())
        return makeError(ErrorCode::InvalidArgument, "a frame has an empty name");
    if (frame.name == SceneGraph::kWorld)
        return makeError(ErrorCode::DuplicateFrame, "'world' is the root frame and cannot be redefined");
    const Transform &t = frame.transform;
    const double qNorm = std::sqrt(glm::dot(t.rotation, t.rotation));
    if (!Checks::finite(t.translation) || !Checks::finite(t.scale) || !std::isfinite(qNorm))
        return makeError(ErrorCode::InvalidArgument, where + "transform must be finite");
    if (std::abs(qNorm - 1.0) > Checks::kOrthonormal)
        return makeError(ErrorCode::NotOrthonormal,
                         where + "rotation quaternion is not of unit length (|q| = " + Checks::str(qNorm) + ")");
    if (t.scale.x == 0.0 || t.scale.y == 0.0 || t.scale.z == 0.0)
        return makeError(ErrorCode::InvalidArgument,
                         where + "scale " + Checks::str(t.scale) + " has a zero component (not invertible)");
    return Ok{};
}

} // namespace

Result<SceneGraph> SceneGraph::create(const std::vector<FrameSpec> &frames)
{
    std::map<std::string, const FrameSpec *> byName;
    for (const FrameSpec &frame : frames) {
        if (auto status = validateFrame(frame); !status)
            return status.error();
        if (!byName.emplace(frame.name, &frame).second)
            return makeError(ErrorCode::DuplicateFrame, "frame '" + frame.name + "' is defined twice");
    }
    for (const FrameSpec &frame : frames)
        if (frame.parent != kWorld && !byName.count(frame.parent))
            return makeError(ErrorCode::UnknownFrame,
                             "frame '" + frame.name + "' has unknown parent '" + frame.parent + "'");

    SceneGraph graph;
    graph.world_[kWorld] = glm::dmat4(1.0);
    // Resolve each frame by walking up to the first resolved ancestor, then composing back down.
    for (const FrameSpec &frame : frames) {
        std::vector<const FrameSpec *> path;
        std::set<std::string> seen;
        const FrameSpec *cursor = &frame;
        while (!graph.world_.count(cursor->name)) {
            if (!seen.insert(cursor->name).second)
                return makeError(ErrorCode::CyclicFrames, "frame '" + frame.name + "' is its own ancestor");
            path.push_back(cursor);
            if (cursor->parent == kWorld)
                break;
            cursor = byName.at(cursor->parent);
        }
        for (auto it = path.rbegin(); it != path.rend(); ++it)
            graph.world_[(*it)->name] = graph.world_.at((*it)->parent) * (*it)->transform.matrix();
    }
    return graph;
}

bool SceneGraph::contains(const std::string &name) const
{
    return world_.count(name) != 0;
}

Result<glm::dmat4> SceneGraph::worldMatrix(const std::string &name) const
{
    auto it = world_.find(name);
    if (it == world_.end())
        return makeError(ErrorCode::UnknownFrame, "unknown frame '" + name + "'");
    return it->second;
}

Result<glm::dmat3> SceneGraph::normalMatrix(const std::string &name) const
{
    auto world = worldMatrix(name);
    if (!world)
        return world.error();
    return glm::inverseTranspose(glm::dmat3(*world));
}

} // namespace overlayd
