// V4l2OutputSink, zero copy per frame: queueing a lease's dmabufs and dropping the lease when the buffer is done.
#include "drivers/v4l2/output_sink.h"

#include <cerrno>

namespace overlayd {

bool V4l2OutputSink::takesLease(const FrameView &frame) const
{
    std::array<DmabufPlane, 3> planes;
    return zeroCopy_ && dmabufPlanes(frame, planes);
}

Status V4l2OutputSink::writeLease(std::shared_ptr<const FrameLease> lease)
{
    if (!streaming_)
        return makeError(ErrorCode::InvalidArgument, describe() + " is not open");
    std::array<DmabufPlane, 3> planes;
    if (!dmabufPlanes(lease->view(), planes))
        return makeError(ErrorCode::InvalidArgument, describe() + ": frame does not match the opened format");
    if (auto dmabuf = useMemory(Memory::Dmabuf); !dmabuf)
        return dmabuf;
    if (auto reclaimed = reclaimLeases(); !reclaimed)
        return reclaimed;
    const std::optional<unsigned> slot = takeLeaseSlot(planes[0].fd);
    if (!slot) {
        ++dropped_; // the device holds every buffer it may: the lease goes back now, as a copy would be dropped
        return Ok{};
    }
    if (auto queued = dmabuf_->queue(*slot, planes, deviceFormat_.numPlanes); !queued) {
        if (queued.error().code == ErrorCode::DeviceLost) {
            releaseLeases(); // the device will never return them, and the capture needs its buffers
        } else if (options_.zeroCopy == ZeroCopy::Auto && zeroCopy_.exchange(false)) {
            log(describe() + ": the driver refused a DMABUF buffer (" + queued.error().message +
                "); copying frames from now on");
        }
        return queued;
    }
    slots_[*slot] = {std::move(lease), planes[0].fd};
    ++written_;
    ++zeroCopied_;
    return Ok{};
}

// A free slot, preferring the one that last held the same dmabuf (vb2 then keeps its import).
std::optional<unsigned> V4l2OutputSink::takeLeaseSlot(int fd)
{
    std::optional<unsigned> any;
    for (unsigned i = 0; i < slots_.size(); ++i) {
        if (slots_[i].lease)
            continue;
        if (slots_[i].lastFd == fd)
            return i;
        if (!any)
            any = i;
    }
    return any;
}

Status V4l2OutputSink::reclaimLeases()
{
    for (;;) {
        unsigned index = 0;
        const int r = dmabuf_->dequeue(index);
        if (r == -EAGAIN)
            return Ok{};
        if (r < 0) {
            Error error = ioctlError(device_->describe() + ": VIDIOC_DQBUF", r);
            if (error.code == ErrorCode::DeviceLost)
                releaseLeases();
            return error;
        }
        slots_[index].lease.reset(); // the last reference gives the buffer back to the capture
    }
}

void V4l2OutputSink::releaseLeases()
{
    for (Slot &slot : slots_)
        slot.lease.reset();
}

uint64_t V4l2OutputSink::heldLeases() const
{
    uint64_t held = 0;
    for (const Slot &slot : slots_)
        held += slot.lease != nullptr;
    return held;
}

} // namespace overlayd