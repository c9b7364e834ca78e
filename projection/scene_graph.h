// SPDX-License-Identifier: Apache-2.0
// Named coordinate frames, each placed relative to its parent (the viewing pipeline's hierarchical coordinate systems).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "base/result.h"

namespace overlayd {

// A frame's placement in its parent: x_parent = T * R * S * x_local.
struct Transform {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0}; // unit quaternion (w, x, y, z)
    glm::dvec3 scale{1.0};

    glm::dmat4 matrix() const;
};

struct FrameSpec {
    std::string name;
    std::string parent; // "world" or another frame's name
    Transform transform;
};

// The frames of a scene, resolved once: each frame's world matrix is the product along its path to "world".
class SceneGraph
{
public:
    static constexpr const char *kWorld = "world";

    // Frames may be listed in any order; unknown parents, duplicates, cycles and bad transforms are refused.
    static Result<SceneGraph> create(const std::vector<FrameSpec> &frames);

    bool contains(const std::string &name) const;
    // world_from_frame; "world" is the identity.
    Result<glm::dmat4> worldMatrix(const std::string &name) const;
    // The inverse transpose of the upper 3x3 of worldMatrix: transforms normals.
    Result<glm::dmat3> normalMatrix(const std::string &name) const;

private:
    std::map<std::string, glm::dmat4> world_;
};

} // namespace overlayd
