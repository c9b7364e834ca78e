// SPDX-License-Identifier: Apache-2.0
// NoSignalFrame: the frame sinks receive while the source is down: dark grey with "NO SIGNAL" and the reason,
// drawn once per reason in RGBA and converted to the stream's own format through the overlay's converters.
#pragma once

#include <string>

#include "base/result.h"
#include "media/frame_buffer.h"
#include "media/stream.h"

namespace overlayd {

class NoSignalFrame
{
public:
    static Result<NoSignalFrame> create(const StreamFormat &format, const std::string &reason);

    FrameView view() { return buffer_.view(); }
    const std::string &reason() const { return reason_; }
    const StreamFormat &format() const { return format_; }

private:
    NoSignalFrame(FrameBuffer buffer, const StreamFormat &format, std::string reason)
        : buffer_(std::move(buffer)), format_(format), reason_(std::move(reason))
    {}

    FrameBuffer buffer_;
    StreamFormat format_;
    std::string reason_;
};

} // namespace overlayd
