// SPDX-License-Identifier: Apache-2.0
// FramePool: the owned frames that a synthetic or replay source fills and lends out as FrameLeases, allocated as the
// pipeline first needs them.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "base/result.h"
#include "media/frame_buffer.h"
#include "media/stream.h"

namespace overlayd {

// Shared between the source and its outstanding leases, so a lease returned after the source is gone is harmless.
class FramePool : public LeaseOwner, public std::enable_shared_from_this<FramePool>
{
public:
    // Checks the format; no frame is allocated yet. At most `capacity` frames are ever lent out at once.
    static Result<std::shared_ptr<FramePool>> create(const StreamFormat &format, unsigned capacity);

    // A buffer that is not lent out, or nothing when the pipeline holds `capacity` of them. A new buffer is
    // allocated only when every one allocated so far is lent out: a pipeline that gives each frame back before it
    // asks for the next (every sink copies, or writes on the pipeline's thread) holds one frame, a zero-copy sink
    // as many as it keeps queued.
    std::optional<unsigned> acquire();
    FrameBuffer &buffer(unsigned index) { return buffers_[index]; }
    // Lends an acquired buffer; destroying the lease makes it available again.
    FrameLease lend(unsigned index, const FrameMetadata &metadata);
    // Gives back an acquired buffer that was not lent (a failed read).
    void release(unsigned index);
    void giveBack(unsigned index) override { release(index); }
    // How many frames are allocated (for tests and the footprint figures).
    size_t allocated() const;

private:
    FramePool(FrameBuffer first, unsigned capacity);

    unsigned capacity_;
    // Reserved to `capacity` up front, so growing never moves a buffer the source is filling.
    std::vector<FrameBuffer> buffers_;
    mutable std::mutex mutex_; // leases may be returned from a sink's worker thread
    std::vector<bool> busy_;
};

} // namespace overlayd
