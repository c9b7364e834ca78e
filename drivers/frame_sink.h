// FrameSink: where overlaid frames go (Y4M, raw, image snapshots, null, V4L2 output).
#pragma once

#include <string>

#include "drivers/stream.h"
#include "projection/result.h"

namespace overlayd {

class FrameSink
{
public:
    virtual ~FrameSink() = default;

    // Called once before the first frame and again whenever the stream's format changes.
    virtual Status open(const StreamFormat &format) = 0;
    // The frame is borrowed for the call only; a sink that needs it later copies it. A sink may be called from
    // its own worker thread (the pipeline queues frames so a slow sink never stalls the source).
    virtual Status write(const FrameView &frame, const FrameMetadata &metadata) = 0;
    // Flushes and closes; called on shutdown and before a re-open.
    virtual Status close() = 0;

    virtual std::string describe() const = 0;
};

} // namespace overlayd
