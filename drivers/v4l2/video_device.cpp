// VideoDevice: enumeration, format and rate, streaming on and off.
#include "drivers/v4l2/video_device.h"

#include <cerrno>
#include <cstring>

namespace overlayd {

namespace {

double fpsOf(const v4l2_fract &interval)
{
    return interval.numerator == 0 ? 0.0 : double(interval.denominator) / interval.numerator;
}

} // namespace

Error ioctlError(const std::string &what, int negativeErrno)
{
    const int e = -negativeErrno;
    const bool lost = e == ENODEV || e == EIO || e == ENXIO || e == EPIPE;
    return makeError(lost ? ErrorCode::DeviceLost : ErrorCode::Io, what + " failed: " + std::strerror(e));
}

int VideoDevice::ioctl(unsigned long request, void *argument) const
{
    int result;
    do
        result = syscalls_.ioctl(fd_.get(), request, argument);
    while (result == -EINTR);
    return result;
}

std::vector<OfferedFormat> VideoDevice::enumerateFormats() const
{
    std::vector<OfferedFormat> offers;
    for (uint32_t index = 0;; ++index) {
        v4l2_fmtdesc desc{};
        desc.index = index;
        desc.type = bufferType_;
        if (ioctl(VIDIOC_ENUM_FMT, &desc) < 0)
            break;
        offers.push_back({desc.pixelformat, enumerateSizes(desc.pixelformat)});
    }
    return offers;
}

std::vector<SizeRange> VideoDevice::enumerateSizes(uint32_t fourcc) const
{
    std::vector<SizeRange> sizes;
    for (uint32_t index = 0;; ++index) {
        v4l2_frmsizeenum size{};
        size.index = index;
        size.pixel_format = fourcc;
        if (ioctl(VIDIOC_ENUM_FRAMESIZES, &size) < 0)
            break;
        if (size.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
            const auto &d = size.discrete;
            sizes.push_back({d.width, d.width, 1, d.height, d.height, 1});
            continue;
        }
        const auto &s = size.stepwise; // stepwise and continuous (step 1) enumerate once
        sizes.push_back({s.min_width, s.max_width, s.step_width, s.min_height, s.max_height, s.step_height});
        break;
    }
    return sizes;
}

std::vector<RateRange> VideoDevice::enumerateRates(uint32_t fourcc, unsigned width, unsigned height) const
{
    std::vector<RateRange> rates;
    for (uint32_t index = 0;; ++index) {
        v4l2_frmivalenum interval{};
        interval.index = index;
        interval.pixel_format = fourcc;
        interval.width = width;
        interval.height = height;
        if (ioctl(VIDIOC_ENUM_FRAMEINTERVALS, &interval) < 0)
            break;
        if (interval.type == V4L2_FRMIVAL_TYPE_DISCRETE) {
            const double fps = fpsOf(interval.discrete);
            rates.push_back({fps, fps});
            continue;
        }
        // The longest interval is the lowest rate.
        rates.push_back({fpsOf(interval.stepwise.max), fpsOf(interval.stepwise.min)});
        break;
    }
    return rates;
}

Result<DeviceFormat> VideoDevice::setFormat(const DeviceFormat &format) const
{
    v4l2_format raw{};
    toV4l2(format, bufferType_, raw);
    if (const int r = ioctl(VIDIOC_S_FMT, &raw); r < 0)
        return ioctlError(describe() + ": VIDIOC_S_FMT " + fourccName(format.fourcc) + " " +
                              std::to_string(format.width) + "x" + std::to_string(format.height),
                          r);
    return fromV4l2(raw);
}

double VideoDevice::setRate(double fps) const
{
    v4l2_streamparm parm{};
    parm.type = bufferType_;
    if (fps <= 0.0 || ioctl(VIDIOC_G_PARM, &parm) < 0)
        return fps;
    const bool capture =
        !(bufferType_ == V4L2_BUF_TYPE_VIDEO_OUTPUT || bufferType_ == V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE);
    uint32_t &capability = capture ? parm.parm.capture.capability : parm.parm.output.capability;
    v4l2_fract &interval = capture ? parm.parm.capture.timeperframe : parm.parm.output.timeperframe;
    if (!(capability & V4L2_CAP_TIMEPERFRAME))
        return fpsOf(interval) > 0.0 ? fpsOf(interval) : fps;
    // A millisecond-resolution fraction keeps 29.97 (30000/1001) close enough for the driver to round to.
    interval = {1000, uint32_t(fps * 1000.0 + 0.5)};
    if (ioctl(VIDIOC_S_PARM, &parm) < 0)
        return fps;
    return fpsOf(interval) > 0.0 ? fpsOf(interval) : fps;
}

Status VideoDevice::streamOn() const
{
    int type = int(bufferType_);
    if (const int r = ioctl(VIDIOC_STREAMON, &type); r < 0)
        return ioctlError(describe() + ": VIDIOC_STREAMON", r);
    return Ok{};
}

Status VideoDevice::streamOff() const
{
    int type = int(bufferType_);
    if (const int r = ioctl(VIDIOC_STREAMOFF, &type); r < 0)
        return ioctlError(describe() + ": VIDIOC_STREAMOFF", r);
    return Ok{};
}

Result<unsigned> VideoDevice::requestBuffers(unsigned count, uint32_t memory) const
{
    v4l2_requestbuffers request{};
    request.count = count;
    request.type = bufferType_;
    request.memory = memory;
    if (const int r = ioctl(VIDIOC_REQBUFS, &request); r < 0)
        return ioctlError(describe() + ": VIDIOC_REQBUFS " + std::to_string(count) +
                              (memory == V4L2_MEMORY_DMABUF ? " DMABUF" : " MMAP") + " buffers",
                          r);
    return unsigned(request.count);
}

void VideoDevice::releaseBuffers(uint32_t memory) const
{
    v4l2_requestbuffers request{};
    request.type = bufferType_;
    request.memory = memory;
    (void)ioctl(VIDIOC_REQBUFS, &request);
}

int VideoDevice::dequeue(uint32_t memory, unsigned count, v4l2_buffer &buffer,
                         std::array<v4l2_plane, VIDEO_MAX_PLANES> &planes) const
{
    prepareBuffer(buffer, planes, bufferType_, memory, 0);
    if (const int r = ioctl(VIDIOC_DQBUF, &buffer); r < 0)
        return r;
    return buffer.index < count ? 0 : -EINVAL;
}

} // namespace overlayd