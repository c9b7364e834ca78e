// SPDX-License-Identifier: Apache-2.0
// FrameSink: where overlaid frames go (Y4M, raw, image snapshots, null, V4L2 output).
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "media/stream.h"

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

    // True for a sink whose write() costs next to nothing and never blocks (the null sink): its worker then calls
    // write() on the pipeline's thread with the frame itself, so it holds no queue, no thread and no frame copies.
    virtual bool writesInline() const { return false; }

    // Zero copy (opt-in: the V4L2 output, and the encoded stream for a V4L2 encoder). takesLease() is asked on the
    // pipeline's thread for every source frame, so it may only read what open() decided; true: the frame goes to
    // writeLease() instead of being copied for write(). writeLease() gets a reference to the source's own buffer and
    // drops it when the device is done with it (the last reference gives the buffer back to the source). It may use
    // only the frame's dmabuf fds, never its mapped bytes: the source may unmap them at any time (stop()).
    virtual bool takesLease(const FrameView &) const { return false; }
    virtual Status writeLease(std::shared_ptr<const FrameLease> lease)
    {
        return write(lease->view(), lease->metadata()); // never reached unless takesLease() says yes
    }
};

} // namespace overlayd
