// openStream: the one sequence that opens a stream, for `run` (each start and reconnect) and `render`.
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "config/daemon_config.h"
#include "daemon/pipeline.h"
#include "daemon/scene_control.h"
#include "daemon/stages.h"
#include "drivers/frame_source.h"

namespace overlayd {

// Which step of openStream failed, so that each caller can word it and choose its exit status.
enum class OpenStep { CreateSource, StartSource, BuildOverlay, OpenSinks };

struct OpenFailure {
    OpenStep step = OpenStep::CreateSource;
    std::string source; // the source's description once it was created
};

// Creates and starts the source (its format negotiated), builds the overlay for that format through SceneControl,
// (re)opens the pipeline's sinks when the format changed (a failure there is fatal only if `sinksMustOpen`), and
// switches the pipeline and SceneControl to the new overlay. On failure nothing is switched and the source is
// stopped.
Result<std::unique_ptr<FrameSource>> openStream(const SourceFactory &makeSource, const DaemonConfig &config,
                                                SceneControl &scene, Pipeline &pipeline, bool sinksMustOpen,
                                                OpenFailure *failure = nullptr);

} // namespace overlayd
