// Camera changes from outside the config file (the HTTP API) read by [camera]'s own readers, and the drop-in file
// that keeps the live pose across restarts without rewriting the user's file.
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

// The drop-in beside a config file that `POST /api/save` writes: "dir/name.toml" -> "dir/name.live.toml". The
// loader reads its [camera] after the main file: its pose replaces the main file's pose, and its intrinsics (when
// it has any) the main file's intrinsics form.
std::string liveDropInPath(const std::string &configPath);
// The drop-in's text: the pose (position + orientation, exact; yaw/pitch/roll in a comment) and, when
// withIntrinsics, the fov or pinhole intrinsics (other forms are refused).
Result<std::string> liveDropInText(const CameraSpec &camera, bool withIntrinsics);
// Writes that text to liveDropInPath(configPath), whole or not at all (a temporary renamed over it); the path written.
// An Io error when the file cannot be written.
Result<std::string> writeLiveDropIn(const std::string &configPath, const CameraSpec &camera, bool withIntrinsics);

} // namespace overlayd
