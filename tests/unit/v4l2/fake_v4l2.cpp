// SPDX-License-Identifier: Apache-2.0
// The fake V4L2 kernel: a device's capabilities, formats, sizes, rates and the ioctl dispatch.
#include "fake_v4l2.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "drivers/v4l2/device_format.h"
#include "media/pixel_format.h"

namespace overlayd::test {

namespace {

uint32_t capsFor(uint32_t type)
{
    const uint32_t caps[] = {0, V4L2_CAP_VIDEO_CAPTURE, V4L2_CAP_VIDEO_OUTPUT};
    if (type == V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE)
        return V4L2_CAP_VIDEO_CAPTURE_MPLANE | V4L2_CAP_STREAMING;
    if (type == V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE)
        return V4L2_CAP_VIDEO_OUTPUT_MPLANE | V4L2_CAP_STREAMING;
    return caps[type] | V4L2_CAP_STREAMING;
}

} // namespace

bool FakeDevice::output() const
{
    return bufferType == V4L2_BUF_TYPE_VIDEO_OUTPUT || bufferType == V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
}

bool FakeDevice::multiPlanar() const
{
    return isMultiPlanar(bufferType);
}

unsigned FakeDevice::memoryPlanes() const
{
    return multiPlanar() ? format.fmt.pix_mp.num_planes : 1;
}

uint32_t FakeDevice::planeLength(unsigned plane) const
{
    // vivid makes room for the header it puts before a multi-planar capture plane's data (data_offset).
    const uint32_t header = multiPlanar() && !output() ? dataOffset[plane] : 0;
    return (multiPlanar() ? format.fmt.pix_mp.plane_fmt[plane].sizeimage : format.fmt.pix.sizeimage) + header;
}

int FakeDevice::ioctl(unsigned long request, void *argument)
{
    switch (request) {
    case VIDIOC_QUERYCAP: {
        auto &cap = *static_cast<v4l2_capability *>(argument);
        cap = {};
        std::strncpy(reinterpret_cast<char *>(cap.card), card.c_str(), sizeof(cap.card) - 1);
        cap.device_caps = capsFor(bufferType);
        cap.capabilities = cap.device_caps | V4L2_CAP_DEVICE_CAPS;
        return 0;
    }
    case VIDIOC_ENUM_FMT: {
        auto &desc = *static_cast<v4l2_fmtdesc *>(argument);
        if (desc.type != bufferType || desc.index >= formats.size())
            return -EINVAL;
        desc.pixelformat = formats[desc.index].fourcc;
        return 0;
    }
    case VIDIOC_ENUM_FRAMESIZES:
        return enumSizes(*static_cast<v4l2_frmsizeenum *>(argument));
    case VIDIOC_ENUM_FRAMEINTERVALS:
        return enumIntervals(*static_cast<v4l2_frmivalenum *>(argument));
    case VIDIOC_S_FMT:
        return setFormat(*static_cast<v4l2_format *>(argument));
    case VIDIOC_G_FMT:
        *static_cast<v4l2_format *>(argument) = format;
        return 0;
    case VIDIOC_G_PARM:
    case VIDIOC_S_PARM:
        return parm(*static_cast<v4l2_streamparm *>(argument), request == VIDIOC_S_PARM);
    case VIDIOC_REQBUFS:
        return requestBuffers(*static_cast<v4l2_requestbuffers *>(argument));
    case VIDIOC_QUERYBUF:
        return queryBuffer(*static_cast<v4l2_buffer *>(argument));
    case VIDIOC_QBUF:
        return queueBuffer(*static_cast<v4l2_buffer *>(argument));
    case VIDIOC_DQBUF:
        return dequeueBuffer(*static_cast<v4l2_buffer *>(argument));
    case VIDIOC_STREAMON:
        streaming = true;
        return 0;
    case VIDIOC_STREAMOFF:
        // As vb2 does: every buffer comes back to the application, dequeued.
        streaming = false;
        for (Buffer &b : buffers)
            b.queued = false;
        queued.clear();
        done.clear();
        return 0;
    default:
        return -ENOTTY;
    }
}

int FakeDevice::enumSizes(v4l2_frmsizeenum &s) const
{
    for (const FakeFormat &f : formats) {
        if (f.fourcc != s.pixel_format)
            continue;
        if (s.index >= f.sizes.size())
            return -EINVAL;
        s.type = V4L2_FRMSIZE_TYPE_DISCRETE;
        s.discrete = {f.sizes[s.index].first, f.sizes[s.index].second};
        return 0;
    }
    return -EINVAL;
}

int FakeDevice::enumIntervals(v4l2_frmivalenum &i) const
{
    for (const FakeFormat &f : formats) {
        if (f.fourcc != i.pixel_format || i.index >= f.rates.size())
            continue;
        i.type = V4L2_FRMIVAL_TYPE_DISCRETE;
        i.discrete = {1000, uint32_t(std::lround(f.rates[i.index] * 1000))};
        return 0;
    }
    return -EINVAL;
}

int FakeDevice::setFormat(v4l2_format &f)
{
    if (f.type != bufferType)
        return -EINVAL;
    if (!buffers.empty())
        return -EBUSY;
    const bool mp = multiPlanar();
    uint32_t fourcc = mp ? f.fmt.pix_mp.pixelformat : f.fmt.pix.pixelformat;
    auto offered =
        std::find_if(formats.begin(), formats.end(), [&](const FakeFormat &o) { return o.fourcc == fourcc; });
    if (offered == formats.end())
        offered = formats.begin(); // drivers substitute a format of their own
    fourcc = offered->fourcc;
    unsigned width = mp ? f.fmt.pix_mp.width : f.fmt.pix.width, height = mp ? f.fmt.pix_mp.height : f.fmt.pix.height;
    auto nearest = std::min_element(offered->sizes.begin(), offered->sizes.end(), [&](auto a, auto b) {
        return std::abs(double(a.first) * a.second - double(width) * height) <
               std::abs(double(b.first) * b.second - double(width) * height);
    });
    width = nearest->first;
    height = nearest->second;

    DeviceFormat out{.fourcc = fourcc, .width = width, .height = height};
    // A capture driver reports its own colorimetry; an output driver takes the application's.
    const DeviceFormat asked = fromV4l2(f);
    out.colorspace = output() ? asked.colorspace : colorspace;
    out.ycbcrEnc = output() ? asked.ycbcrEnc : ycbcrEnc;
    out.quantization = output() ? asked.quantization : quantization;
    const PixelFormatInfo *info = pixelFormatForDevice(fourcc);
    if (!info) { // compressed
        out.planes[0] = {0, width * height * 2};
    } else if (mp && multiPlaneVariant(info->fourcc) == fourcc) {
        out.numPlanes = info->numPlanes;
        for (unsigned p = 0; p < info->numPlanes; ++p) {
            const uint32_t bpl = info->minStride(p, width) + padding[p];
            out.planes[p] = {bpl, bpl * info->planeHeight(p, height)};
        }
    } else {
        const uint32_t bpl = info->minStride(0, width) + padding[0];
        uint32_t size = 0;
        for (unsigned p = 0; p < info->numPlanes; ++p)
            size += bpl * info->planes[p].bytesPerGroup / info->planes[0].bytesPerGroup * info->planeHeight(p, height);
        out.planes[0] = {bpl, size};
    }
    toV4l2(out, bufferType, f);
    format = f;
    if (fps == 0.0 && !offered->rates.empty())
        fps = offered->rates[0];
    return 0;
}

int FakeDevice::parm(v4l2_streamparm &p, bool set)
{
    if (p.type != bufferType)
        return -EINVAL;
    v4l2_captureparm &c = p.parm.capture; // capture and output share the layout of these two fields
    if (set && c.timeperframe.numerator != 0) {
        const double wanted = double(c.timeperframe.denominator) / c.timeperframe.numerator;
        const uint32_t fourcc = multiPlanar() ? format.fmt.pix_mp.pixelformat : format.fmt.pix.pixelformat;
        for (const FakeFormat &f : formats) {
            if (f.fourcc != fourcc || f.rates.empty())
                continue;
            fps = *std::min_element(f.rates.begin(), f.rates.end(),
                                    [&](double a, double b) { return std::abs(a - wanted) < std::abs(b - wanted); });
        }
    }
    c.capability = V4L2_CAP_TIMEPERFRAME;
    c.timeperframe = {1000, uint32_t(std::lround(fps * 1000))};
    return 0;
}

} // namespace overlayd::test
