// SPDX-License-Identifier: Apache-2.0
// VideoDevice: one opened V4L2 video node, its capabilities, and the ioctls the source and sink need.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/result.h"
#include "base/unique_fd.h"
#include "drivers/v4l2/device_format.h"
#include "drivers/v4l2/negotiation.h"
#include "drivers/v4l2/v4l2_syscalls.h"

namespace overlayd {

enum class Direction { Capture, Output };

class VideoDevice
{
public:
    // `device` is a path (symlinks such as /dev/v4l/by-id/... resolve through open) or, when it does not start
    // with '/', a card name looked up among /dev/video*. Fails unless the node streams in `direction`.
    static Result<std::unique_ptr<VideoDevice>> open(Syscalls &syscalls, const std::string &device,
                                                     Direction direction);

    Syscalls &syscalls() const { return syscalls_; }
    int fd() const { return fd_.get(); }
    uint32_t bufferType() const { return bufferType_; }
    bool multiPlanar() const { return isMultiPlanar(bufferType_); }
    // "/dev/video0 (vivid)"
    std::string describe() const { return path_ + " (" + card_ + ")"; }

    // The ioctl through the seam, EINTR retried: 0 or -errno.
    int ioctl(unsigned long request, void *argument) const;

    std::vector<OfferedFormat> enumerateFormats() const;
    std::vector<RateRange> enumerateRates(uint32_t fourcc, unsigned width, unsigned height) const;

    Result<DeviceFormat> setFormat(const DeviceFormat &format) const;
    // Asks for `fps` (VIDIOC_S_PARM) and answers the rate in effect; `fps` itself when the driver has no control.
    double setRate(double fps) const;
    Status streamOn() const;
    Status streamOff() const;
    // VIDIOC_REQBUFS `count` buffers of `memory` (V4L2_MEMORY_MMAP or _DMABUF): the count the driver granted.
    Result<unsigned> requestBuffers(unsigned count, uint32_t memory) const;
    // VIDIOC_REQBUFS 0: frees the driver's buffers (stream off first); nothing to do if the device is gone.
    void releaseBuffers(uint32_t memory) const;
    // VIDIOC_DQBUF of a `memory` buffer into buffer/planes (prepared here): 0, -errno, or -EINVAL for an index at or
    // past `count` (a driver that answers a buffer it was never given).
    int dequeue(uint32_t memory, unsigned count, v4l2_buffer &buffer,
                std::array<v4l2_plane, VIDEO_MAX_PLANES> &planes) const;

private:
    VideoDevice(Syscalls &syscalls, UniqueFd fd, std::string path, std::string card, uint32_t bufferType)
        : syscalls_(syscalls), fd_(std::move(fd)), path_(std::move(path)), card_(std::move(card)),
          bufferType_(bufferType)
    {}

    std::vector<SizeRange> enumerateSizes(uint32_t fourcc) const;

    Syscalls &syscalls_;
    UniqueFd fd_;
    std::string path_, card_;
    uint32_t bufferType_;
};

// An ioctl failure as an Error: ENODEV/EIO/ENXIO/EPIPE are DeviceLost, the rest Io; the message names the call.
Error ioctlError(const std::string &what, int negativeErrno);

} // namespace overlayd
