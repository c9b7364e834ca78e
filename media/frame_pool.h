// FramePool: a few owned frames that a synthetic or replay source fills and lends out as FrameLeases.
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
class FramePool : public std::enable_shared_from_this<FramePool>
{
public:
    static Result<std::shared_ptr<FramePool>> create(const StreamFormat &format, unsigned count);

    // A buffer that is not lent out, or nothing when the pipeline holds all of them.
    std::optional<unsigned> acquire();
    FrameBuffer &buffer(unsigned index) { return buffers_[index]; }
    // Lends an acquired buffer; destroying the lease makes it available again.
    FrameLease lend(unsigned index, const FrameMetadata &metadata);
    // Gives back an acquired buffer that was not lent (a failed read).
    void release(unsigned index);

private:
    explicit FramePool(std::vector<FrameBuffer> buffers) : buffers_(std::move(buffers)), busy_(buffers_.size()) {}

    std::vector<FrameBuffer> buffers_;
    std::mutex mutex_; // leases may be returned from a sink's worker thread
    std::vector<bool> busy_;
};

} // namespace overlayd
