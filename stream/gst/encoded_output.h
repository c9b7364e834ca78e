// SPDX-License-Identifier: Apache-2.0
// EncodedOutput: an encoded sink that takes the encoder's access units through push(), as RtspOutput does: the
// recording and the push, each with a pipeline of its own fed through a BranchFeed.
#pragma once

#include <gst/gst.h>

#include "base/result.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd {

class EncodedOutput
{
public:
    virtual ~EncodedOutput() = default;
    // Starts on `context` (the engine's main loop): what cannot start at all is the error; what may come back (a
    // server, disk space) is retried on the loop.
    virtual Status start(GMainContext *context) = 0;
    // One access unit with its caps, on the encoder's streaming thread: must not block.
    virtual void push(GstSample *sample) = 0;
    virtual EncodedSinkState state() const = 0;
};

} // namespace overlayd
