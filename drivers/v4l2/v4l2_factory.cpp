// Placeholder until the V4L2 capture source and output sink land: asking for them is a clear error.
#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeV4l2Source(const SourceOptions &)
{
    return makeError(ErrorCode::Unsupported, "V4L2 capture is not implemented yet");
}

Result<std::unique_ptr<FrameSink>> makeV4l2OutputSink(const SinkOptions &)
{
    return makeError(ErrorCode::Unsupported, "V4L2 output is not implemented yet");
}

} // namespace overlayd
