// SPDX-License-Identifier: Apache-2.0
// The projection queries `overlayd project` and `unproject` print and the HTTP API's /api/project and /api/unproject
// answer: where world points land in a Camera and why a point has no visible pixel, and the world ray behind a pixel
// and where it meets a plane. Here, below both, so that neither includes the other.
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "projection/camera.h"
#include "projection/geometry.h"

namespace overlayd {

// What `project` says of a point beside its pixel: how far in front of the camera it is (metres along the optical
// axis; negative behind), and why it has no visible pixel: "behind-camera", "before-near", "beyond-far",
// "outside-image-circle" (no pixel), "outside-viewport", "outside-scissor" (a pixel, not drawn); null when visible.
struct PointReport {
    double distance = 0.0;
    const char *reason = nullptr;
};
PointReport explainPoint(const Camera &camera, const glm::dvec3 &world, const ProjectedPoint &point);

// What `project` prints for world points (--json, or the text form), pixels in the viewport's origin; the HTTP API's
// /api/project answers the JSON.
std::string projectJson(const Camera &camera, const std::vector<glm::dvec3> &world);
std::string projectText(const Camera &camera, const std::vector<glm::dvec3> &world);
// What `unproject` prints for pixels given in the viewport's origin: each one's world ray and where it meets `plane`.
std::string unprojectJson(const Camera &camera, const Plane &plane, const std::vector<glm::dvec2> &pixels);
std::string unprojectText(const Camera &camera, const Plane &plane, const std::vector<glm::dvec2> &pixels);

// `project --json`: [{"world":[x,y,z],"pixel":[u,v] or null,"depth":d or null,"distance":m,"visible":bool,
// "reason":r or null}, ...]; numbers are printed in their shortest exact (round-trip) form.
std::string projectionsJson(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points,
                            const std::vector<PointReport> &reports);
// The same for people, one line per point.
std::string projectionsText(const std::vector<glm::dvec3> &world, const std::vector<ProjectedPoint> &points,
                            const std::vector<PointReport> &reports);

} // namespace overlayd
