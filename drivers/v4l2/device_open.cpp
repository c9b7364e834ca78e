// VideoDevice::open: by path or card name, with the capability checks.
#include "drivers/v4l2/video_device.h"

#include <fcntl.h>

#include <cstring>
#include <optional>
#include <utility>

namespace overlayd {

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