// makeSource: the one place that maps a configured source kind to its implementation.
#include "drivers/source_options.h"

#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeSource(const SourceOptions &options)
{
    switch (options.kind) {
    case SourceKind::V4l2:
        return makeV4l2Source(options);
    case SourceKind::Synthetic:
    case SourceKind::Replay:
        break;
    }
    return makeError(ErrorCode::Unsupported, "this source kind is not implemented yet");
}

} // namespace overlayd
