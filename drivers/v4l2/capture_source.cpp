// SPDX-License-Identifier: Apache-2.0
// V4l2CaptureSource: opening, negotiation and the start of streaming; then dequeuing frames, lending them as
// leases, and giving them back.
#include "drivers/v4l2/capture_source.h"

#include <algorithm>
#include <cerrno>
#include <utility>

namespace overlayd {

V4l2CaptureSource::V4l2CaptureSource(Syscalls &syscalls, SourceOptions options, LogFunction log)
    : syscalls_(syscalls), options_(std::move(options)), log_(std::move(log))
{}

V4l2CaptureSource::~V4l2CaptureSource()
{
    stop();
}

std::string V4l2CaptureSource::describe() const
{
    return device_ ? device_->describe() : options_.v4l2.device;
}

Result<StreamFormat> V4l2CaptureSource::start()
{
    stop();
    auto device = VideoDevice::open(syscalls_, options_.v4l2.device, Direction::Capture);
    if (!device)
        return device.error();
    device_ = std::move(device.value());
    auto format = negotiate();
    if (!format)
        stop();
    return format;
}

void V4l2CaptureSource::stop()
{
    // First, so that no give-back from a sink thread is in the middle of a QBUF while the buffers go.
    if (hub_)
        hub_->detach();
    hub_.reset();
    if (streaming_ && device_)
        (void)device_->streamOff(); // a vanished device cannot stream off; the buffers are freed either way
    streaming_ = false;
    decoded_.clear();
    pool_.reset();
    decoder_.reset();
    device_.reset();
}

Result<DeviceFormat> V4l2CaptureSource::applyFormat(uint32_t fourcc, unsigned width, unsigned height)
{
    DeviceFormat wanted{.fourcc = fourcc, .width = width, .height = height};
    const PixelFormatInfo *info = pixelFormatForDevice(fourcc);
    if (info && multiPlaneVariant(info->fourcc) == fourcc)
        wanted.numPlanes = info->numPlanes;
    return device_->setFormat(wanted);
}

Result<StreamFormat> V4l2CaptureSource::negotiate()
{
    const PixelFormatInfo *wanted = options_.pixelFormat;
    const std::vector<OfferedFormat> offers = device_->enumerateFormats();
    const FormatChoice choice = chooseFormat({wanted, options_.width, options_.height, options_.fps}, offers);
    if (choice.verdict == Verdict::Invalid)
        return makeError(ErrorCode::ConfigError, device_->describe() + " " + choice.message);
    auto got = applyFormat(choice.fourcc, choice.width, choice.height);
    if (!got)
        return got.error();
    mjpeg_ = isMjpeg(got->fourcc);
    const PixelFormatInfo *info = mjpeg_ ? &mjpegOutputFormat(wanted) : pixelFormatForDevice(got->fourcc);
    if (!info)
        return makeError(ErrorCode::Unsupported, device_->describe() + " answered VIDIOC_S_FMT with " +
                                                     fourccName(got->fourcc) + ", which overlayd does not handle");
    if (mjpeg_) {
        auto decoder = makeMjpegDecoder();
        if (!decoder)
            return decoder.error();
        decoder_ = std::move(decoder.value());
    }
    const double fps =
        device_->setRate(chooseRate(options_.fps, device_->enumerateRates(got->fourcc, got->width, got->height)));
    // JPEG is BT.601 full range (JFIF) whatever the driver says about the compressed stream.
    const Colorimetry reported = mjpeg_ ? Colorimetry{YcbcrMatrix::Bt601, ColourRange::Full}
                                        : colorimetryFromV4l2(got->colorspace, got->ycbcrEnc, got->quantization);
    stream_ = {info,
               got->width,
               got->height,
               mjpeg_ ? 0 : got->planes[0].bytesPerLine,
               options_.colorimetry.value_or(reported),
               fps};
    noteAdjustment(stream_, got->fourcc);
    if (auto started = startStreaming(*got); !started)
        return started.error();
    return stream_;
}

void V4l2CaptureSource::noteAdjustment(const StreamFormat &got, uint32_t deviceFourcc)
{
    const std::string asked =
        describeMode(options_.width, options_.height, options_.fps, std::string(options_.pixelFormat->name));
    std::string answer = describeMode(got.width, got.height, got.fps, std::string(got.format->name));
    if (mjpeg_)
        answer += " (decoded from " + fourccName(deviceFourcc) + ")";
    adjustment_ = asked == answer ? std::string() : device_->describe() + ": asked " + asked + ", got " + answer;
    // Once per distinct adjustment, so that a camera re-plugged every minute does not fill the journal.
    if (!adjustment_.empty() && adjustment_ != lastLogged_ && log_)
        log_(adjustment_);
    if (!adjustment_.empty())
        lastLogged_ = adjustment_;
}

Status V4l2CaptureSource::startStreaming(const DeviceFormat &format)
{
    auto pool = BufferPool::create(*device_, options_.v4l2.bufferCount, format, mjpeg_ ? nullptr : stream_.format);
    if (!pool)
        return pool.error();
    pool_ = std::move(pool.value());
    for (unsigned i = 0; mjpeg_ && i < pool_->size(); ++i) {
        auto buffer = FrameBuffer::allocate(stream_);
        if (!buffer)
            return buffer.error();
        decoded_.push_back(std::move(buffer.value()));
    }
    std::vector<UniqueFd> dmabufs = exportBuffers();
    stream_.dmabufBuffers = dmabufs.empty() ? 0 : pool_->size();
    hub_ = std::make_shared<LeaseHub>(*pool_, std::move(dmabufs));
    for (unsigned i = 0; i < pool_->size(); ++i) {
        if (auto queued = hub_->queue(i); !queued)
            return queued;
    }
    if (auto on = device_->streamOn(); !on)
        return on;
    streaming_ = true;
    sequence_.restart();
    dropped_ = decodeFailures_ = 0;
    return Ok{};
}

// Only when asked (a zero-copy sink wants the fds) and never for MJPEG, whose frames are our decoded copies. A
// driver that cannot export is not an error: the frames go without fds and zero-copy sinks copy (logged once).
std::vector<UniqueFd> V4l2CaptureSource::exportBuffers()
{
    if (!options_.v4l2.exportDmabuf || mjpeg_)
        return {};
    auto exported = pool_->exportDmabufs();
    if (exported)
        return std::move(exported.value());
    if (!exportFailureLogged_ && log_)
        log_(exported.error().message + ": buffers not exportable, frames carry no dmabuf fds");
    exportFailureLogged_ = true;
    return {};
}

// V4l2CaptureSource: dequeuing frames, lending them as leases, and giving them back.

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
