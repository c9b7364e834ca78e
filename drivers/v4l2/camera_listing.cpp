// SPDX-License-Identifier: Apache-2.0
// list-cameras for V4L2: every capture node under /dev with its formats, frame sizes and discrete frame rates.
#include <fcntl.h>
#include <linux/videodev2.h>

#include <cstdio>
#include <cstring>

#include "drivers/camera_list.h"
#include "drivers/v4l2/v4l2_syscalls.h"
#include "media/pixel_format.h"

namespace overlayd {

namespace {

// Enumeration answers are bounded: a driver that never says EINVAL must not loop forever.
constexpr unsigned kMaxEntries = 256;

std::string fourccName(uint32_t fourcc)
{
    std::string name;
    for (int i = 0; i < 4; ++i)
        name += char((fourcc >> (8 * i)) & 0xff);
    while (!name.empty() && name.back() == ' ')
        name.pop_back();
    return name;
}

std::vector<double> frameRates(Syscalls &sys, int fd, uint32_t fourcc, uint32_t width, uint32_t height)
{
    std::vector<double> rates;
    for (unsigned i = 0; i < kMaxEntries; ++i) {
        v4l2_frmivalenum interval{};
        interval.index = i;
        interval.pixel_format = fourcc;
        interval.width = width;
        interval.height = height;
        if (sys.ioctl(fd, VIDIOC_ENUM_FRAMEINTERVALS, &interval) < 0 || interval.type != V4L2_FRMIVAL_TYPE_DISCRETE)
            break;
        if (interval.discrete.numerator > 0)
            rates.push_back(double(interval.discrete.denominator) / interval.discrete.numerator);
    }
    return rates;
}

CameraMode modeOf(Syscalls &sys, int fd, uint32_t fourcc)
{
    const PixelFormatInfo *info = pixelFormatFromFourcc(fourcc);
    CameraMode mode{info ? std::string(info->name) : fourccName(fourcc), info || fourcc == V4L2_PIX_FMT_MJPEG, {}, {}};
    for (unsigned i = 0; i < kMaxEntries; ++i) {
        v4l2_frmsizeenum size{};
        size.index = i;
        size.pixel_format = fourcc;
        if (sys.ioctl(fd, VIDIOC_ENUM_FRAMESIZES, &size) < 0)
            break;
        if (size.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
            mode.sizes.push_back(std::to_string(size.discrete.width) + "x" + std::to_string(size.discrete.height));
            if (i == 0)
                mode.fps = frameRates(sys, fd, fourcc, size.discrete.width, size.discrete.height);
        } else {
            const auto &s = size.stepwise;
            mode.sizes.push_back(std::to_string(s.min_width) + "x" + std::to_string(s.min_height) + "-" +
                                 std::to_string(s.max_width) + "x" + std::to_string(s.max_height) + " (step " +
                                 std::to_string(s.step_width) + "x" + std::to_string(s.step_height) + ")");
            break;
        }
    }
    return mode;
}

} // namespace

std::vector<CameraDescription> listV4l2Cameras()
{
    Syscalls &sys = realSyscalls();
    std::vector<CameraDescription> out;
    for (const std::string &path : sys.videoDevices()) {
        const int opened = sys.open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (opened < 0) {
            out.push_back({"v4l2", path, "", std::string("cannot open: ") + std::strerror(-opened), {}});
            continue;
        }
        const UniqueFd fd(sys, opened);
        v4l2_capability caps{};
        if (sys.ioctl(fd.get(), VIDIOC_QUERYCAP, &caps) < 0)
            continue;
        const uint32_t device = (caps.capabilities & V4L2_CAP_DEVICE_CAPS) ? caps.device_caps : caps.capabilities;
        const bool multiPlanar = device & V4L2_CAP_VIDEO_CAPTURE_MPLANE;
        if (!(device & (V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_VIDEO_CAPTURE_MPLANE)))
            continue; // output, metadata and subdevice-like nodes cannot be a source
        CameraDescription description{"v4l2", path, reinterpret_cast<const char *>(caps.card), "", {}};
        for (unsigned i = 0; i < kMaxEntries; ++i) {
            v4l2_fmtdesc format{};
            format.index = i;
            format.type = multiPlanar ? V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE : V4L2_BUF_TYPE_VIDEO_CAPTURE;
            if (sys.ioctl(fd.get(), VIDIOC_ENUM_FMT, &format) < 0)
                break;
            description.modes.push_back(modeOf(sys, fd.get(), format.pixelformat));
        }
        out.push_back(std::move(description));
    }
    return out;
}

} // namespace overlayd
