// SPDX-License-Identifier: Apache-2.0
// VideoDevice: opening by path or card name with the capability checks, enumeration, format and rate, streaming on
// and off.
#include "drivers/v4l2/video_device.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <optional>
#include <utility>

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

// VideoDevice::open: by path or card name, with the capability checks.

namespace {

struct Probe {
    UniqueFd fd;
    std::string card;
    uint32_t bufferType = 0; // 0: cannot stream in the wanted direction
};

uint32_t bufferTypeFor(uint32_t caps, Direction direction)
{
    if (!(caps & V4L2_CAP_STREAMING))
        return 0;
    if (direction == Direction::Capture)
        return (caps & V4L2_CAP_VIDEO_CAPTURE)          ? V4L2_BUF_TYPE_VIDEO_CAPTURE
               : (caps & V4L2_CAP_VIDEO_CAPTURE_MPLANE) ? V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE
                                                        : 0;
    return (caps & V4L2_CAP_VIDEO_OUTPUT)          ? V4L2_BUF_TYPE_VIDEO_OUTPUT
           : (caps & V4L2_CAP_VIDEO_OUTPUT_MPLANE) ? V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE
                                                   : 0;
}

Result<Probe> probe(Syscalls &syscalls, const std::string &path, Direction direction)
{
    const int fd = syscalls.open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const ErrorCode code = (fd == -ENOENT || fd == -ENODEV || fd == -ENXIO) ? ErrorCode::NotFound : ErrorCode::Io;
        const char *hint = fd == -EACCES ? " (is the user in the 'video' group?)" : "";
        return makeError(code, "cannot open " + path + ": " + std::strerror(-fd) + hint);
    }
    Probe result{UniqueFd(syscalls, fd), {}, 0};
    v4l2_capability cap{};
    if (const int r = syscalls.ioctl(fd, VIDIOC_QUERYCAP, &cap); r < 0)
        return makeError(ErrorCode::Io, path + " is not a V4L2 device (VIDIOC_QUERYCAP: " + std::strerror(-r) + ")");
    const uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    result.card.assign(reinterpret_cast<const char *>(cap.card),
                       strnlen(reinterpret_cast<const char *>(cap.card), sizeof(cap.card)));
    result.bufferType = bufferTypeFor(caps, direction);
    return result;
}

const char *directionName(Direction direction)
{
    return direction == Direction::Capture ? "video capture" : "video output";
}

// The first streaming node whose card is `name`, else the first whose card starts with it.
Result<std::pair<std::string, Probe>> findByCard(Syscalls &syscalls, const std::string &name, Direction direction)
{
    std::string seen;
    std::optional<std::pair<std::string, Probe>> prefixMatch;
    for (const std::string &path : syscalls.videoDevices()) {
        auto candidate = probe(syscalls, path, direction);
        if (!candidate)
            continue;
        seen += (seen.empty() ? "" : ", ") + path + " '" + candidate->card + "'";
        if (candidate->bufferType == 0)
            continue;
        if (candidate->card == name)
            return std::pair{path, std::move(candidate.value())};
        if (!prefixMatch && candidate->card.starts_with(name))
            prefixMatch.emplace(path, std::move(candidate.value()));
    }
    if (prefixMatch)
        return std::move(*prefixMatch);
    return makeError(ErrorCode::NotFound, std::string("no ") + directionName(direction) + " device with card name '" +
                                              name + "' (found: " + (seen.empty() ? "none" : seen) + ")");
}

} // namespace

Result<std::unique_ptr<VideoDevice>> VideoDevice::open(Syscalls &syscalls, const std::string &device,
                                                       Direction direction)
{
    if (device.empty())
        return makeError(ErrorCode::InvalidArgument, "V4L2 device name is empty");
    std::pair<std::string, Probe> found;
    if (device.front() == '/') {
        auto probed = probe(syscalls, device, direction);
        if (!probed)
            return probed.error();
        found = {device, std::move(probed.value())};
    } else {
        auto byCard = findByCard(syscalls, device, direction);
        if (!byCard)
            return byCard.error();
        found = std::move(byCard.value());
    }
    auto &[path, probed] = found;
    if (probed.bufferType == 0)
        return makeError(ErrorCode::Unsupported,
                         path + " (" + probed.card + ") is not a streaming " + directionName(direction) + " device");
    return std::unique_ptr<VideoDevice>(
        new VideoDevice(syscalls, std::move(probed.fd), path, probed.card, probed.bufferType));
}

} // namespace overlayd
