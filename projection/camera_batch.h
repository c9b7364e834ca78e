// SPDX-License-Identifier: Apache-2.0
// Batch projection of points, one entry per instruction set; Camera::projectPoints picks one at run time.
#pragma once

#include <cstddef>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "camera.h"
#include "point_path.h"

namespace overlayd {

struct BatchJob {
    const PointPath &path;
    const glm::dmat4 &viewProjection;
    DistortionModel model;
    const glm::dvec3 *world;
    ProjectedPoint *out;
    std::size_t count;
};

namespace baseline {
void projectPoints(const BatchJob &job); // 2-lane registers: SSE2 on x86-64, NEON on arm64
}
namespace avx2 {
void projectPoints(const BatchJob &job); // 4-lane registers; only on x86-64 CPUs that report AVX2
}
namespace avx512 {
void projectPoints(const BatchJob &job); // 8-lane registers; only on x86-64 CPUs that report AVX-512F
}

} // namespace overlayd
