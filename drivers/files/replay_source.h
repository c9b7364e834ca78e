// SPDX-License-Identifier: Apache-2.0
// Replay sources: Y4M files, raw frame files and PNG/JPEG image sequences, optionally looping.
#pragma once

#include <memory>

#include "base/result.h"
#include "drivers/source_options.h"

namespace overlayd {

// ReplayFormat::Auto picks by the path: ".y4m" is Y4M; a %d in it, ".png", ".jpg" or ".jpeg" are images;
// anything else is raw frames. Nothing is opened until start().
Result<std::unique_ptr<FrameSource>> makeReplaySource(const SourceOptions &options);

} // namespace overlayd
