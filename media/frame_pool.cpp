// SPDX-License-Identifier: Apache-2.0
// FramePool: frames allocated on demand up to the capacity, and lease bookkeeping.
#include "media/frame_pool.h"

#include <algorithm>

namespace overlayd {

Result<std::shared_ptr<FramePool>> FramePool::create(const StreamFormat &format, unsigned capacity)
{
    // The first frame is allocated here: every source lends at least one, and it validates the format.
    auto first = FrameBuffer::allocate(format);
    if (!first)
        return first.error();
    return std::shared_ptr<FramePool>(new FramePool(std::move(*first), std::max(capacity, 1u)));
}

FramePool::FramePool(FrameBuffer first, unsigned capacity) : capacity_(capacity)
{
    buffers_.reserve(capacity_);
    busy_.reserve(capacity_);
    buffers_.push_back(std::move(first));
    busy_.push_back(false);
}

std::optional<unsigned> FramePool::acquire()
{
    std::lock_guard lock(mutex_);
    for (unsigned i = 0; i < busy_.size(); ++i) {
        if (!busy_[i]) {
            busy_[i] = true;
            return i;
        }
    }
    if (buffers_.size() == capacity_)
        return std::nullopt;
    // The first frame's format was accepted, so another of the same cannot be refused.
    buffers_.push_back(buffers_.front().alike());
    busy_.push_back(true);
    return unsigned(buffers_.size() - 1);
}

FrameLease FramePool::lend(unsigned index, const FrameMetadata &metadata)
{
    return FrameLease(buffers_[index].view(), metadata, shared_from_this(), index);
}

void FramePool::release(unsigned index)
{
    std::lock_guard lock(mutex_);
    busy_[index] = false;
}

size_t FramePool::allocated() const
{
    std::lock_guard lock(mutex_);
    return buffers_.size();
}

} // namespace overlayd
