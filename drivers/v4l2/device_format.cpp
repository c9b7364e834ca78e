// SPDX-License-Identifier: Apache-2.0
// Conversions between DeviceFormat and v4l2_format; the fourcc alias table.
#include "drivers/v4l2/device_format.h"

#include <algorithm>

namespace overlayd {

namespace {

struct PlaneVariant {
    uint32_t contiguous, separate;
};

// Formats whose planes may come in separate buffers under the multi-planar API. One table, no switch.
constexpr PlaneVariant kPlaneVariants[] = {
    {V4L2_PIX_FMT_NV12, V4L2_PIX_FMT_NV12M},     {V4L2_PIX_FMT_NV21, V4L2_PIX_FMT_NV21M},
    {V4L2_PIX_FMT_NV16, V4L2_PIX_FMT_NV16M},     {V4L2_PIX_FMT_YUV420, V4L2_PIX_FMT_YUV420M},
    {V4L2_PIX_FMT_YVU420, V4L2_PIX_FMT_YVU420M},
};

} // namespace

bool isMultiPlanar(uint32_t bufferType)
{
    return bufferType == V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE || bufferType == V4L2_BUF_TYPE_VIDEO_OUTPUT_MPLANE;
}

void prepareBuffer(v4l2_buffer &buffer, std::array<v4l2_plane, VIDEO_MAX_PLANES> &planes, uint32_t type,
                   uint32_t memory, unsigned index)
{
    buffer = {};
    planes = {};
    buffer.type = type;
    buffer.memory = memory;
    buffer.index = index;
    if (isMultiPlanar(type)) {
        buffer.m.planes = planes.data();
        buffer.length = VIDEO_MAX_PLANES;
    }
}

void toV4l2(const DeviceFormat &format, uint32_t bufferType, v4l2_format &out)
{
    out = {};
    out.type = bufferType;
    if (isMultiPlanar(bufferType)) {
        v4l2_pix_format_mplane &mp = out.fmt.pix_mp;
        mp.width = format.width;
        mp.height = format.height;
        mp.pixelformat = format.fourcc;
        mp.field = format.field;
        mp.num_planes = uint8_t(format.numPlanes);
        for (unsigned p = 0; p < format.numPlanes && p < VIDEO_MAX_PLANES; ++p)
            mp.plane_fmt[p] = {format.planes[p].sizeImage, format.planes[p].bytesPerLine, {}};
        mp.colorspace = format.colorspace;
        mp.ycbcr_enc = uint8_t(format.ycbcrEnc);
        mp.quantization = uint8_t(format.quantization);
        return;
    }
    v4l2_pix_format &pix = out.fmt.pix;
    pix.width = format.width;
    pix.height = format.height;
    pix.pixelformat = format.fourcc;
    pix.field = format.field;
    pix.bytesperline = format.planes[0].bytesPerLine;
    pix.sizeimage = format.planes[0].sizeImage;
    pix.colorspace = format.colorspace;
    pix.ycbcr_enc = format.ycbcrEnc;
    pix.quantization = format.quantization;
}

DeviceFormat fromV4l2(const v4l2_format &in)
{
    DeviceFormat format;
    if (isMultiPlanar(in.type)) {
        const v4l2_pix_format_mplane &mp = in.fmt.pix_mp;
        format = {mp.pixelformat, mp.width,     mp.height,      mp.field, std::clamp<unsigned>(mp.num_planes, 1, 3), {},
                  mp.colorspace,  mp.ycbcr_enc, mp.quantization};
        for (unsigned p = 0; p < format.numPlanes; ++p)
            format.planes[p] = {mp.plane_fmt[p].bytesperline, mp.plane_fmt[p].sizeimage};
        return format;
    }
    const v4l2_pix_format &pix = in.fmt.pix;
    format = {pix.pixelformat, pix.width,     pix.height,      pix.field, 1, {},
              pix.colorspace,  pix.ycbcr_enc, pix.quantization};
    format.planes[0] = {pix.bytesperline, pix.sizeimage};
    return format;
}

std::string fourccName(uint32_t fourcc)
{
    std::string name;
    for (unsigned i = 0; i < 4; ++i) {
        const char c = char((fourcc >> (8 * i)) & 0xff);
        if (c != ' ' && c != '\0')
            name += (c >= 32 && c < 127) ? c : '?';
    }
    return name;
}

const PixelFormatInfo *pixelFormatForDevice(uint32_t fourcc)
{
    for (const PlaneVariant &variant : kPlaneVariants) {
        if (variant.separate == fourcc)
            return pixelFormatFromFourcc(variant.contiguous);
    }
    return pixelFormatFromFourcc(fourcc);
}

uint32_t multiPlaneVariant(uint32_t fourcc)
{
    for (const PlaneVariant &variant : kPlaneVariants) {
        if (variant.contiguous == fourcc)
            return variant.separate;
    }
    return 0;
}

bool isMjpeg(uint32_t fourcc)
{
    return fourcc == V4L2_PIX_FMT_MJPEG || fourcc == V4L2_PIX_FMT_JPEG;
}

} // namespace overlayd
