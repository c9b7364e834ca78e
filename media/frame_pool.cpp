// FramePool: allocation up front (sizes validated by FrameBuffer::allocate) and lease bookkeeping.
#include "media/frame_pool.h"

namespace overlayd {

Result<std::shared_ptr<FramePool>> FramePool::create(const StreamFormat &format, unsigned count)
{
    std::vector<FrameBuffer> buffers;
    for (unsigned i = 0; i < count; ++i) {
        auto buffer = FrameBuffer::allocate(format);
        if (!buffer)
            return buffer.error();
        buffers.push_back(std::move(*buffer));
    }
    return std::shared_ptr<FramePool>(new FramePool(std::move(buffers)));
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
    return std::nullopt;
}

FrameLease FramePool::lend(unsigned index, const FrameMetadata &metadata)
{
    std::shared_ptr<FramePool> self = shared_from_this();
    return FrameLease(buffers_[index].view(), metadata, [self, index] { self->release(index); });
}

void FramePool::release(unsigned index)
{
    std::lock_guard lock(mutex_);
    busy_[index] = false;
}

} // namespace overlayd
