// SPDX-License-Identifier: Apache-2.0
// openStream: the one sequence that opens a stream, for `run` (each start, reconnect and reload) and `render`.
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "config/daemon_config.h"
#include "control/scene_control.h"
#include "daemon/pipeline.h"
#include "daemon/stages.h"
#include "drivers/frame_source.h"

namespace overlayd {

// Which step of openStream failed, so that each caller can word it and choose its exit status.
enum class OpenStep { CreateSource, StartSource, BuildOverlay, OpenSinks };

struct OpenFailure {
    OpenStep step = OpenStep::CreateSource;
    std::string source; // the source's description once it was created
};

// A stream that is open but does not run yet: the started source, its negotiated format and the overlay built for
// that format.
struct OpenedStream {
    std::unique_ptr<FrameSource> source;
    StreamFormat format;
    std::unique_ptr<OverlayRenderer> renderer;
};

// Creates and starts the source (its format negotiated) and builds the overlay for that format from `scene` (the
// live SceneControl, or a reload's candidate). Nothing that runs is touched; on failure the source is stopped.
Result<OpenedStream> startStream(const SourceFactory &makeSource, const DaemonConfig &config, const SceneControl &scene,
                                 OpenFailure *failure = nullptr);

// The stream becomes the pipeline's: frames are blended with its overlay, and `scene`'s changes go to it. The
// pipeline's sinks must already be open for its format. Returns the source, for the caller to pull frames from.
std::unique_ptr<FrameSource> runStream(OpenedStream stream, SceneControl &scene, Pipeline &pipeline);

// startStream, then (re)opens the pipeline's sinks when the format changed (a failure there is fatal only if
// `sinksMustOpen`), then runStream. On failure nothing is switched and the source is stopped.
Result<std::unique_ptr<FrameSource>> openStream(const SourceFactory &makeSource, const DaemonConfig &config,
                                                SceneControl &scene, Pipeline &pipeline, bool sinksMustOpen,
                                                OpenFailure *failure = nullptr);

} // namespace overlayd
