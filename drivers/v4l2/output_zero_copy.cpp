// V4l2OutputSink, zero copy: the choice at open, the DMABUF queue that holds capture buffers (as lease references)
// until the device is done with them, and the switch to MMAP for frames of our own.
#include "drivers/v4l2/output_sink.h"

#include <algorithm>
#include <cerrno>

namespace overlayd {

void V4l2OutputSink::placePlanes(const PixelFormatInfo &info, unsigned width, unsigned height)
{
    placed_ = {};
    if (deviceFormat_.numPlanes == info.numPlanes) { // one memory plane per format plane (YUYV, NV12M)
        for (unsigned p = 0; p < info.numPlanes; ++p) {
            const unsigned stride = deviceFormat_.planes[p].bytesPerLine;
            placed_[p] = {p, 0, stride ? stride : info.minStride(p, width)};
        }
        return;
    }
    // One memory plane holding every format plane, strides derived from plane 0's as V4L2 defines them.
    auto layout = makeFrameLayout(info, width, height, deviceFormat_.planes[0].bytesPerLine);
    for (unsigned p = 0; layout && p < info.numPlanes; ++p)
        placed_[p] = {0, layout->planes[p].offset, layout->planes[p].stride};
}

std::string V4l2OutputSink::zeroCopyRefusal(const StreamFormat &format)
{
    if (format.dmabufBuffers == 0)
        return "the frames carry no dmabuf fds (the source is not a V4L2 camera, decodes MJPEG, or its driver "
               "refused VIDIOC_EXPBUF)";
    if (format.dmabufBuffers < 3)
        return "the capture has " + std::to_string(format.dmabufBuffers) +
               " buffers and keeps 2 to capture into (raise the source's buffers)";
    if (format.stride != 0 && placed_[0].stride != format.stride)
        return "the output's bytesperline " + std::to_string(placed_[0].stride) + " differs from the capture's " +
               std::to_string(format.stride);
    // The capture must keep two buffers of its own, or a sink holding the rest would stall it.
    leaseSlots_ = std::min(options_.bufferCount, format.dmabufBuffers - 2);
    auto queue = DmabufQueue::create(*device_, leaseSlots_);
    if (!queue)
        return queue.error().message;
    leaseSlots_ = std::min(leaseSlots_, (*queue)->size());
    dmabuf_ = std::move(queue.value());
    return {};
}

Status V4l2OutputSink::chooseMemory(const StreamFormat &format)
{
    zeroCopy_ = false;
    if (options_.zeroCopy != ZeroCopy::Off) {
        const std::string refusal = zeroCopyRefusal(format);
        if (refusal.empty()) {
            zeroCopy_ = true;
            memory_ = Memory::Dmabuf;
            slots_.assign(leaseSlots_, Slot{});
            log(describe() + ": zero copy: the capture buffers are queued by DMABUF, up to " +
                std::to_string(leaseSlots_) + " at a time");
            return Ok{};
        }
        if (options_.zeroCopy == ZeroCopy::On)
            return makeError(ErrorCode::ConfigError, describe() + ": zero_copy = \"on\" is impossible: " + refusal);
        log(describe() + ": copying frames (no zero copy: " + refusal + ")");
    }
    return useMemory(Memory::Mmap);
}

// A V4L2 queue has one memory type: switching streams off (which returns every buffer, and so every lease),
// frees the old buffers and requests the new. Only frames of our own (NO SIGNAL) make a zero-copy sink switch.
Status V4l2OutputSink::useMemory(Memory memory)
{
    if (memory_ == memory)
        return Ok{};
    // After a failed switch memory_ is None with the stream off: the next frame tries again.
    if (streaming_)
        (void)device_->streamOff();
    releaseLeases();
    slots_.assign(memory == Memory::Dmabuf ? leaseSlots_ : 0, Slot{});
    free_.clear();
    pool_.reset();
    dmabuf_.reset();
    memory_ = Memory::None;
    if (memory == Memory::Mmap) {
        auto pool = BufferPool::create(*device_, options_.bufferCount, deviceFormat_, stream_.format);
        if (!pool)
            return pool.error();
        pool_ = std::move(pool.value());
        for (unsigned i = 0; i < pool_->size(); ++i)
            free_.push_back(i);
    } else {
        auto queue = DmabufQueue::create(*device_, leaseSlots_);
        if (!queue)
            return queue.error();
        dmabuf_ = std::move(queue.value());
    }
    memory_ = memory;
    return streaming_ ? device_->streamOn() : Ok{};
}

bool V4l2OutputSink::dmabufPlanes(const FrameView &frame, std::array<DmabufPlane, 3> &planes) const
{
    if (!stream_.format || frame.format != stream_.format || frame.width != stream_.width ||
        frame.height != stream_.height)
        return false;
    planes = {};
    std::array<size_t, 3> base{}, end{};
    for (unsigned p = 0; p < stream_.format->numPlanes; ++p) {
        const PlaneView &view = frame.planes[p];
        const PlacedPlane &want = placed_[p];
        if (view.dmabufFd < 0 || view.stride != want.stride || view.dmabufOffset < want.offset)
            return false;
        DmabufPlane &memory = planes[want.memoryPlane];
        const size_t start = view.dmabufOffset - want.offset;
        if (memory.fd < 0) {
            memory.fd = view.dmabufFd;
            base[want.memoryPlane] = start;
        } else if (memory.fd != view.dmabufFd || base[want.memoryPlane] != start) {
            return false; // the planes are not where the output's format puts them
        }
        end[want.memoryPlane] = std::max(end[want.memoryPlane], view.dmabufOffset + view.size);
    }
    for (unsigned m = 0; m < deviceFormat_.numPlanes; ++m) {
        const size_t sizeImage =
            deviceFormat_.planes[m].sizeImage ? deviceFormat_.planes[m].sizeImage : end[m] - base[m];
        // Multi-planar bytesused counts from the start of the dmabuf; the single-planar API has no data_offset.
        if (base[m] + sizeImage > end[m] || end[m] > UINT32_MAX || (!device_->multiPlanar() && base[m] != 0))
            return false;
        planes[m].dataOffset = uint32_t(base[m]);
        planes[m].bytesUsed = uint32_t(base[m] + sizeImage);
        planes[m].length = uint32_t(end[m]);
    }
    return true;
}

} // namespace overlayd