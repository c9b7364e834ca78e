// makeSink: the one place that maps a configured sink kind to its implementation.
#include "drivers/sink_options.h"

#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSink>> makeSink(const SinkOptions &options)
{
    if (options.kind == SinkKind::V4l2Output)
        return makeV4l2OutputSink(options);
    return makeError(ErrorCode::Unsupported, "this sink kind is not implemented yet");
}

} // namespace overlayd
