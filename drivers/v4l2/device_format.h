// SPDX-License-Identifier: Apache-2.0
// DeviceFormat: one shape for the single- and multi-planar v4l2_format, and fourcc helpers.
#pragma once

#include <linux/videodev2.h>

#include <array>
#include <cstdint>
#include <string>

#include "media/pixel_format.h"

namespace overlayd {

struct DevicePlane {
    uint32_t bytesPerLine = 0;
    uint32_t sizeImage = 0;
};

// What VIDIOC_G/S/TRY_FMT say, whichever API the device speaks. numPlanes counts memory planes: 1 for the
// single-planar API and for NV12 in the multi-planar API; 2 for NV12M.
struct DeviceFormat {
    uint32_t fourcc = 0;
    uint32_t width = 0, height = 0;
    uint32_t field = V4L2_FIELD_NONE;
    unsigned numPlanes = 1;
    std::array<DevicePlane, 3> planes{};
    uint32_t colorspace = 0, ycbcrEnc = 0, quantization = 0;
};

void toV4l2(const DeviceFormat &format, uint32_t bufferType, v4l2_format &out);
DeviceFormat fromV4l2(const v4l2_format &in);
bool isMultiPlanar(uint32_t bufferType);
// A v4l2_buffer for QUERYBUF/QBUF/DQBUF; with the multi-planar API it points at `planes`, which must outlive it.
void prepareBuffer(v4l2_buffer &buffer, std::array<v4l2_plane, VIDEO_MAX_PLANES> &planes, uint32_t type,
                   uint32_t memory, unsigned index);

// "YUYV", "MJPG": the four characters, for messages.
std::string fourccName(uint32_t fourcc);

// The table entry for a device fourcc, including the multi-memory-plane variants (NV12M is NV12 split over two
// buffers): nullptr for formats the table does not have.
const PixelFormatInfo *pixelFormatForDevice(uint32_t fourcc);
// The multi-memory-plane variant of a table format (NV12 -> NV12M), or 0 when there is none.
uint32_t multiPlaneVariant(uint32_t fourcc);

bool isMjpeg(uint32_t fourcc);

} // namespace overlayd
