// CameraSpec: the camera as configured (pose, intrinsics, distortion, viewport), resolved to a Camera once the
// stream's frame size is known (a V4L2 device may adjust the size; intrinsics then scale with it).
#pragma once

#include <optional>

#include "projection/camera.h"
#include "projection/distortion.h"
#include "projection/pose.h"
#include "projection/result.h"
#include "projection/viewport.h"

namespace overlayd {

class CameraSpec
{
public:
    // The Camera for a frame of width x height. Intrinsics given for another image size (calibration) are scaled
    // to this one; the viewport's frame size is this one.
    Result<Camera> build(unsigned frameWidth, unsigned frameHeight) const;

    // Filled by the config loader (config/camera_spec.cpp and the loader own the details).
    Pose pose{}; // world to camera; a camera mounted on a scene-graph frame is resolved to world when loading
    // ... the config helper adds the intrinsics forms, distortion, near/far, depth range and viewport fields here.
};

} // namespace overlayd
