// SPDX-License-Identifier: Apache-2.0
// The drop-in beside a config file that keeps the live camera across restarts without rewriting the user's file:
// written by `POST /api/save` and `solve-pose --write`, read by the loader after the main file.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"
#include "config/camera_spec.h"

namespace overlayd {

// "dir/name.toml" -> "dir/name.live.toml". The loader reads its [camera] after the main file's: its pose replaces
// the main file's pose, its intrinsics form the main file's intrinsics form, any other key the main file's key.
std::string liveDropInPath(const std::string &configPath);

// The drop-in's text: `existing` (its current text, "" when there is none) with every camera key that makes the
// live camera replaced by `camera`'s (pose as rmat/tvec, the intrinsics form, calibration_crop, near, far,
// depth_range, distortion), numbers in their shortest exact form, so that the loaded config projects exactly as
// `camera` does; any other key it holds is kept. `writer` names the command in the header comment. An error naming
// the drop-in when `existing` is not TOML.
Result<std::string> liveDropInText(const CameraSpec &camera, std::string_view existing, std::string_view writer,
                                   const std::string &dropInName = "the drop-in");

// Merges `camera` into liveDropInPath(configPath) as liveDropInText does and replaces the file whole (see
// base/replace_file.h); the path written. Io when it cannot be read or written, ConfigError when it is not TOML.
Result<std::string> writeLiveDropIn(const std::string &configPath, const CameraSpec &camera, std::string_view writer);

} // namespace overlayd
