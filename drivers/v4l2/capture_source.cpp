// V4l2CaptureSource: opening, negotiation and the start of streaming.
#include "drivers/v4l2/capture_source.h"

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

} // namespace overlayd