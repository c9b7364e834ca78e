// SPDX-License-Identifier: Apache-2.0
// The synthetic source: deterministic patterns in any format and size, and the checkerboard-ground scene.
#pragma once

#include <memory>

#include "base/result.h"
#include "drivers/source_options.h"

namespace overlayd {

// Validates the options (size, fps, format, the scene's camera) before anything is allocated. The
// checkerboard-scene pattern is rendered through `sceneCamera` (required for it, ignored otherwise).
Result<std::unique_ptr<FrameSource>> makeSyntheticSource(const SourceOptions &options, const Camera *sceneCamera);

} // namespace overlayd
