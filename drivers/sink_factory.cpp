// makeSink: the one place that maps a configured sink kind to its implementation.
#include "drivers/sink_options.h"

#include "drivers/files/file_sinks.h"
#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSink>> makeSink(const SinkOptions &options)
{
    switch (options.kind) {
    case SinkKind::Y4m:
        return makeY4mSink(options);
    case SinkKind::Raw:
        return makeRawSink(options);
    case SinkKind::Snapshot:
        return makeSnapshotSink(options);
    case SinkKind::Null:
        return makeNullSink(options);
    case SinkKind::V4l2Output:
        return makeV4l2OutputSink(options);
    }
    return makeError(ErrorCode::InvalidArgument, "unknown sink kind");
}

} // namespace overlayd
