// SPDX-License-Identifier: Apache-2.0
// Camera changes from outside the config file (the HTTP API) read by [camera]'s own readers.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"
#include "config/camera_spec.h"

namespace overlayd {

// Limits of a request body's JSON: nesting (a [camera] table is at most 3 deep) and size.
inline constexpr size_t kMaxCameraRequestDepth = 8;

// A JSON object of [camera] keys: one pose form (any of the config file's), and/or intrinsics keys (an intrinsics
// form, near/far, depth_range, distortion), applied over the live camera and composed for a width x height stream.
// Refused with "camera.KEY: reason; ..." (every problem, in the config loader's words) when anything is wrong;
// `calibration` and `frame` are not accepted (they name files and frames of the config file).
Result<CameraSpec> cameraFromJson(std::string_view json, const CameraSpec &live, unsigned width, unsigned height);

} // namespace overlayd
