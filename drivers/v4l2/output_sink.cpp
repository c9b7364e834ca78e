// SPDX-License-Identifier: Apache-2.0
// V4l2OutputSink: format set-up, buffer recycling and the stride-aware copy; then zero copy: the choice at open, the
// DMABUF queue, and each lease queued and dropped when the device is done with it.
#include "drivers/v4l2/output_sink.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace overlayd {

namespace {

// The V4L2 fields that name a colorimetry, so that readers of the output see the stream's own. RGB frames are
// sRGB, full range, whatever the pipeline's YCbCr colorimetry says.
void setColorimetry(DeviceFormat &format, const PixelFormatInfo &info, const Colorimetry &colorimetry)
{
    if (info.encoding == ColourEncoding::Rgb) {
        format.colorspace = V4L2_COLORSPACE_SRGB;
        format.quantization = V4L2_QUANTIZATION_FULL_RANGE;
        return;
    }
    const bool is601 = colorimetry.matrix == YcbcrMatrix::Bt601;
    format.colorspace = is601 ? V4L2_COLORSPACE_SMPTE170M : V4L2_COLORSPACE_REC709;
    format.ycbcrEnc = is601 ? V4L2_YCBCR_ENC_601 : V4L2_YCBCR_ENC_709;
    format.quantization =
        colorimetry.range == ColourRange::Full ? V4L2_QUANTIZATION_FULL_RANGE : V4L2_QUANTIZATION_LIM_RANGE;
}

} // namespace

std::string V4l2OutputSink::describe() const
{
    return "v4l2 output " + (device_ ? device_->describe() : options_.path);
}

void V4l2OutputSink::log(const std::string &line) const
{
    if (log_)
        log_(line);
}

Status V4l2OutputSink::open(const StreamFormat &format)
{
    (void)close();
    if (!format.format)
        return makeError(ErrorCode::InvalidArgument, "V4L2 output needs a pixel format");
    auto device = VideoDevice::open(syscalls_, options_.path, Direction::Output);
    if (!device)
        return device.error();
    device_ = std::move(device.value());
    if (auto set = setFormat(format); !set)
        return set;
    stream_ = format;
    (void)device_->setRate(format.fps);
    if (auto chosen = chooseMemory(format); !chosen)
        return chosen;
    if (auto on = device_->streamOn(); !on)
        return on;
    streaming_ = true;
    return Ok{};
}

Status V4l2OutputSink::setFormat(const StreamFormat &format)
{
    DeviceFormat wanted{.fourcc = format.format->fourcc, .width = format.width, .height = format.height};
    setColorimetry(wanted, *format.format, format.colorimetry);
    // Zero copy needs the output to read rows where the capture wrote them: ask for the capture's stride.
    if (options_.zeroCopy != ZeroCopy::Off && format.dmabufBuffers > 0)
        wanted.planes[0].bytesPerLine = format.stride;
    auto got = device_->setFormat(wanted);
    if (got && got->fourcc != wanted.fourcc && device_->multiPlanar() && multiPlaneVariant(wanted.fourcc) != 0) {
        // A multi-planar device may offer NV12 only as NV12M: the same frame in one buffer per plane.
        wanted.fourcc = multiPlaneVariant(wanted.fourcc);
        wanted.numPlanes = format.format->numPlanes;
        got = device_->setFormat(wanted);
    }
    if (!got)
        return got.error();
    if (got->fourcc != wanted.fourcc || got->width != wanted.width || got->height != wanted.height)
        return makeError(ErrorCode::ConfigError, device_->describe() + " cannot output " + format.describe() +
                                                     " (it offers " + fourccName(got->fourcc) + " " +
                                                     std::to_string(got->width) + "x" + std::to_string(got->height) +
                                                     ")");
    deviceFormat_ = *got;
    placePlanes(*format.format, format.width, format.height);
    return Ok{};
}

Status V4l2OutputSink::close()
{
    if (device_ && streaming_)
        (void)device_->streamOff(); // a vanished device cannot stream off; the buffers are freed either way
    releaseLeases();
    slots_.clear();
    free_.clear();
    pool_.reset();
    dmabuf_.reset();
    if (device_ && options_.zeroCopy != ZeroCopy::Off && streaming_)
        log(describe() + ": " + std::to_string(written_) + " frames out: " + std::to_string(zeroCopied_) +
            " zero-copy, " + std::to_string(written_ - zeroCopied_) + " copied, " + std::to_string(dropped_) +
            " dropped");
    memory_ = Memory::None;
    streaming_ = false;
    zeroCopy_ = false;
    device_.reset();
    return Ok{};
}

Status V4l2OutputSink::reclaim()
{
    for (;;) {
        Dequeued done;
        const int r = pool_->dequeue(done);
        if (r == -EAGAIN)
            return Ok{};
        if (r < 0)
            return ioctlError(device_->describe() + ": VIDIOC_DQBUF", r);
        free_.push_back(done.index);
    }
}

Status V4l2OutputSink::copyInto(unsigned index, const FrameView &frame)
{
    const FrameView target = pool_->view(index);
    const PixelFormatInfo &info = *frame.format;
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        const size_t rowBytes = info.minStride(p, frame.width);
        for (unsigned y = 0; y < info.planeHeight(p, frame.height); ++y)
            std::memcpy(target.planes[p].data + size_t(y) * target.planes[p].stride,
                        frame.planes[p].data + size_t(y) * frame.planes[p].stride, rowBytes);
    }
    // Whole planes as the driver sized them (sizeimage); the mapping's length where a driver leaves that 0.
    std::array<uint32_t, 3> bytesUsed{};
    for (unsigned p = 0; p < deviceFormat_.numPlanes; ++p) {
        const uint32_t sizeImage = deviceFormat_.planes[p].sizeImage;
        const uint32_t length = uint32_t(pool_->memory(index, p).length);
        bytesUsed[p] = sizeImage != 0 && sizeImage <= length ? sizeImage : length;
    }
    return pool_->queue(index, bytesUsed);
}

Status V4l2OutputSink::write(const FrameView &frame, const FrameMetadata &)
{
    if (!streaming_)
        return makeError(ErrorCode::InvalidArgument, describe() + " is not open");
    if (frame.format != stream_.format || frame.width != stream_.width || frame.height != stream_.height)
        return makeError(ErrorCode::InvalidArgument, describe() + ": frame does not match the opened format");
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    // In zero-copy mode a frame of our own (NO SIGNAL) needs MMAP buffers to be copied into.
    if (auto mmap = useMemory(Memory::Mmap); !mmap)
        return mmap;
    if (auto reclaimed = reclaim(); !reclaimed)
        return reclaimed;
    if (free_.empty()) {
        ++dropped_;
        return Ok{};
    }
    const unsigned index = free_.back();
    free_.pop_back();
    if (auto queued = copyInto(index, frame); !queued)
        return queued;
    ++written_;
    return Ok{};
}

// V4l2OutputSink, zero copy: the choice at open, the DMABUF queue that holds capture buffers (as lease references)
// until the device is done with them, and the switch to MMAP for frames of our own.

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

// V4l2OutputSink, zero copy per frame: queueing a lease's dmabufs and dropping the lease when the buffer is done.

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
