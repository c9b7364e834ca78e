// SPDX-License-Identifier: Apache-2.0
// FrameBuffer: an owned frame in one allocation, laid out by FrameLayout (synthetic and replay sources, sink
// queues, NO SIGNAL frames).
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "media/frame.h"
#include "media/stream.h"

namespace overlayd {

class FrameBuffer
{
public:
    // Refuses absurd sizes before allocating (see kMaxFrameDimension in frame.h).
    static Result<FrameBuffer> allocate(const StreamFormat &format);
    // Another buffer with this one's layout (a pool growing: the layout was checked when the first was allocated).
    FrameBuffer alike() const { return FrameBuffer(layout_); }

    FrameView view() { return layout_.view(bytes_.data()); }
    const FrameLayout &layout() const { return layout_; }
    uint8_t *data() { return bytes_.data(); }
    const uint8_t *data() const { return bytes_.data(); }
    size_t size() const { return bytes_.size(); }

    // Copies the visible bytes of every plane (strides may differ); the frames must share format and size.
    Status copyFrom(const FrameView &source);

private:
    explicit FrameBuffer(const FrameLayout &layout) : layout_(layout), bytes_(layout.totalSize) {}

    FrameLayout layout_;
    std::vector<uint8_t> bytes_;
};

} // namespace overlayd
