// V4l2OutputSink: format set-up, buffer recycling and the stride-aware copy.
#include "drivers/v4l2/output_sink.h"

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

} // namespace overlayd