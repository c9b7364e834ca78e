// SPDX-License-Identifier: Apache-2.0
// FrameSource: where frames come from (synthetic, replay, V4L2). The daemon's event loop drives it.
#pragma once

#include <string>

#include "base/result.h"
#include "media/stream.h"

namespace overlayd {

class FrameSource
{
public:
    virtual ~FrameSource() = default;

    // Opens the device or file and negotiates; the answer is the format frames will have. Any adjustment
    // against what was configured is logged once by the source.
    virtual Result<StreamFormat> start() = 0;
    virtual void stop() = 0;

    // A file descriptor that becomes readable when a frame is ready (a V4L2 device), or -1 when the daemon
    // paces the source itself with a timer at the stream's fps (synthetic, replay).
    virtual int eventFd() const = 0;

    // The next frame, never blocking for long. Errors: TryAgain (nothing ready), EndOfStream (a finite source
    // is done), DeviceLost (tear down and retry with back-off), Malformed/Io (the message names file and frame).
    virtual Result<FrameLease> nextFrame() = 0;

    // "synthetic checkerboard-scene", "/dev/video0 (vivid)": for logs and STATUS=.
    virtual std::string describe() const = 0;
};

} // namespace overlayd
