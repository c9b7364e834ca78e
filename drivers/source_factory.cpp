// SPDX-License-Identifier: Apache-2.0
// makeSource: the one place that maps a configured source kind to its implementation.
#include "drivers/source_options.h"

#include "drivers/files/replay_source.h"
#include "drivers/libcamera/libcamera_factory.h"
#include "drivers/synthetic/synthetic_source.h"
#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeSource(const SourceOptions &options, const Camera *sceneCamera)
{
    // The config loader resolves the name; options made in code must name a table entry too.
    if (!options.pixelFormat)
        return makeError(ErrorCode::InvalidArgument, "no pixel format");
    switch (options.kind) {
    case SourceKind::V4l2:
        return makeV4l2Source(options);
    case SourceKind::Synthetic:
        return makeSyntheticSource(options, sceneCamera);
    case SourceKind::Replay:
        return makeReplaySource(options);
    case SourceKind::Libcamera:
        return makeLibcameraSource(options);
    }
    return makeError(ErrorCode::InvalidArgument, "unknown source kind");
}

} // namespace overlayd
