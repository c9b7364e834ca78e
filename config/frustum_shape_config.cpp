// SPDX-License-Identifier: Apache-2.0
// The frustum annotation: another camera, described with the same pose and intrinsics keys as [camera].
#include "config/config_sections.h"

#include <cmath>

namespace overlayd {

Shape readFrustumShape(TableReader &t, const std::string &baseDirectory)
{
    FrustumShape s;
    s.farDistance = t.positive("far_distance", 1e6).value_or(s.farDistance);
    auto camera = t.table("camera");
    if (!camera)
        return s;
    CameraSpec spec;
    CameraKeys keys;
    const bool posed = readPose(*camera, spec.pose);
    readIntrinsics(*camera, baseDirectory, spec, keys);
    // A field of view needs the other camera's image aspect (width / height); 4:3 unless given.
    const double aspect = camera->positive("aspect", 100.0).value_or(4.0 / 3.0);
    camera->finish();
    if (!posed)
        return s;
    const int height = 1000, width = int(std::lround(aspect * height));
    auto viewport = Viewport::create(ViewportSpec{width, height});
    auto projection = viewport ? spec.buildProjection(*viewport) : Result<Projection>(viewport.error());
    if (!projection) {
        camera->problem(keys.intrinsics, projection.error().message);
        return s;
    }
    s.pose = spec.pose;
    s.projection = projection->matrix();
    s.depth = projection->depthRange();
    return s;
}

} // namespace overlayd
