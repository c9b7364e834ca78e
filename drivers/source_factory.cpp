// makeSource: the one place that maps a configured source kind to its implementation.
#include "drivers/source_options.h"

#include "drivers/files/replay_source.h"
#include "drivers/synthetic/synthetic_source.h"
#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeSource(const SourceOptions &options)
{
    switch (options.kind) {
    case SourceKind::V4l2:
        return makeV4l2Source(options);
    case SourceKind::Synthetic:
        return makeSyntheticSource(options);
    case SourceKind::Replay:
        return makeReplaySource(options);
    }
    return makeError(ErrorCode::InvalidArgument, "unknown source kind");
}

} // namespace overlayd
