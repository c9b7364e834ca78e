// SPDX-License-Identifier: Apache-2.0
// Frame layouts and the checks that keep a blend inside the buffer.
#include "media/frame.h"

#include <string>

namespace overlayd {

namespace {

size_t planeBytes(const PixelFormatInfo &format, unsigned plane, unsigned width, unsigned height, unsigned stride)
{
    const unsigned rows = format.planeHeight(plane, height);
    return rows == 0 ? 0 : size_t(stride) * (rows - 1) + format.minStride(plane, width);
}

} // namespace

FrameView FrameLayout::view(uint8_t *base) const
{
    FrameView frame{format, width, height, {}};
    for (unsigned p = 0; p < format->numPlanes; ++p)
        frame.planes[p] = {base + planes[p].offset, planes[p].stride, planes[p].size};
    return frame;
}

Result<FrameLayout> makeFrameLayout(const PixelFormatInfo &format, unsigned width, unsigned height, unsigned stride)
{
    if (width == 0 || height == 0)
        return makeError(ErrorCode::InvalidArgument,
                         "frame size must be > 0 (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    if (width > kMaxFrameDimension || height > kMaxFrameDimension)
        return makeError(ErrorCode::InvalidArgument, "frame size " + std::to_string(width) + "x" +
                                                         std::to_string(height) + " exceeds the limit of " +
                                                         std::to_string(kMaxFrameDimension) + " per side");
    const unsigned minStride = format.minStride(0, width);
    if (stride == 0)
        stride = minStride;
    if (stride < minStride)
        return makeError(ErrorCode::InvalidArgument, std::string(format.name) + " stride " + std::to_string(stride) +
                                                         " is below " + std::to_string(minStride) + " for width " +
                                                         std::to_string(width));

    FrameLayout layout{&format, width, height, {}, 0};
    for (unsigned p = 0; p < format.numPlanes; ++p) {
        const unsigned bpg0 = format.planes[0].bytesPerGroup;
        const unsigned planeStride = (stride * format.planes[p].bytesPerGroup + bpg0 - 1) / bpg0;
        const size_t size = size_t(planeStride) * format.planeHeight(p, height);
        layout.planes[p] = {layout.totalSize, planeStride, size};
        layout.totalSize += size;
    }
    return layout;
}

Status checkFrame(const FrameView &frame)
{
    if (!frame.format)
        return makeError(ErrorCode::InvalidArgument, "frame has no pixel format");
    const PixelFormatInfo &format = *frame.format;
    for (unsigned p = 0; p < format.numPlanes; ++p) {
        const PlaneView &plane = frame.planes[p];
        const bool strideOk = plane.stride >= format.minStride(p, frame.width);
        if (!plane.data || !strideOk || plane.size < planeBytes(format, p, frame.width, frame.height, plane.stride))
            return makeError(ErrorCode::InvalidArgument, std::string(format.name) + " plane " + std::to_string(p) +
                                                             " is missing or too small for " +
                                                             std::to_string(frame.width) + "x" +
                                                             std::to_string(frame.height));
    }
    return Ok{};
}

} // namespace overlayd
