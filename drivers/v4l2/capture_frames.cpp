// V4l2CaptureSource: dequeuing frames, lending them as leases, and giving them back.
#include "drivers/v4l2/capture_source.h"

#include <algorithm>
#include <cerrno>
#include <utility>

namespace overlayd {

Result<FrameLease> V4l2CaptureSource::nextFrame()
{
    if (!streaming_)
        return makeError(ErrorCode::DeviceLost, describe() + " is not streaming");
    if (auto failed = hub_->takeError())
        return *failed;
    Dequeued buffer;
    if (const int r = hub_->dequeue(buffer); r < 0) // EINTR is retried inside
        return failDequeue(r);

    dropped_ += sequence_.advance(buffer.sequence);

    if (buffer.flags & V4L2_BUF_FLAG_ERROR) {
        // The driver says the data is corrupt (a USB glitch): skip it, as a drop.
        ++dropped_;
        requeue(buffer.index);
        return makeError(ErrorCode::TryAgain, describe() + ": frame marked corrupt by the driver");
    }
    return deliver(buffer);
}

Result<FrameLease> V4l2CaptureSource::failDequeue(int negativeErrno)
{
    if (negativeErrno != -EAGAIN)
        return ioctlError(describe() + ": VIDIOC_DQBUF", negativeErrno);
    // vb2 answers POLLERR while buffers are queued only when the queue is in error (the device went away).
    if (hub_->queuedCount() > 0) {
        pollfd fd{device_->fd(), POLLIN, 0};
        if (syscalls_.poll(&fd, 1, 0) > 0 && (fd.revents & POLLERR))
            return makeError(ErrorCode::DeviceLost, describe() + " reports an error (POLLERR)");
    }
    return makeError(ErrorCode::TryAgain, describe() + ": no frame ready");
}

Result<FrameLease> V4l2CaptureSource::deliver(const Dequeued &buffer)
{
    FrameMetadata metadata;
    metadata.sequence = sequence_.relative(buffer.sequence);
    metadata.timestamp = buffer.timestamp;
    metadata.wallClock = std::chrono::system_clock::now();
    metadata.colorimetry = stream_.colorimetry;

    FrameView view = pool_->view(buffer.index);
    const bool oneMemoryPlane = pool_->memoryPlaneCount() == 1;
    for (unsigned p = 0; p < 3 && !mjpeg_; ++p) {
        // Data that starts after a header (multi-planar API only; vivid does it): one memory plane shifts all.
        const uint32_t wanted = buffer.dataOffset[oneMemoryPlane ? 0 : p];
        const uint32_t offset = std::min<uint32_t>(wanted, uint32_t(view.planes[p].size));
        view.planes[p].data += view.planes[p].data ? offset : 0;
        view.planes[p].size -= offset;
        view.planes[p].dmabufOffset += offset;
    }
    if (mjpeg_) {
        const PlaneMemory memory = pool_->memory(buffer.index, 0);
        const size_t used = std::min<size_t>(buffer.bytesUsed[0], memory.length);
        view = decoded_[buffer.index].view();
        if (auto decoded = decoder_->decode({memory.data, used}, view); !decoded) {
            // USB cameras send a broken JPEG now and then: skip it as a drop (the first one of a start() is
            // logged) rather than fail the stream.
            requeue(buffer.index);
            ++dropped_;
            const std::string message =
                describe() + " frame " + std::to_string(metadata.sequence) + ": " + decoded.error().message;
            if (decodeFailures_++ == 0 && log_)
                log_(message + " (skipped; further broken frames are only counted)");
            return makeError(ErrorCode::TryAgain, message);
        }
    }
    // The lease holds the hub, not the source: its last owner may be a sink thread, and may outlive stop().
    return FrameLease(view, metadata, hub_, buffer.index);
}

void V4l2CaptureSource::requeue(unsigned index)
{
    // A failed QBUF (device gone) is reported by the next nextFrame().
    if (hub_)
        hub_->giveBack(index);
}

} // namespace overlayd