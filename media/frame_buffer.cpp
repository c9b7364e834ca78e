// SPDX-License-Identifier: Apache-2.0
// FrameBuffer: allocation after validation, and a stride-aware copy.
#include "media/frame_buffer.h"

#include <algorithm>
#include <cstring>

namespace overlayd {

Result<FrameBuffer> FrameBuffer::allocate(const StreamFormat &format)
{
    if (!format.format)
        return makeError(ErrorCode::InvalidArgument, "frame buffer needs a pixel format");
    auto layout = makeFrameLayout(*format.format, format.width, format.height, format.stride);
    if (!layout)
        return layout.error();
    return FrameBuffer(*layout);
}

Status FrameBuffer::copyFrom(const FrameView &source)
{
    if (source.format != layout_.format || source.width != layout_.width || source.height != layout_.height)
        return makeError(ErrorCode::InvalidArgument, "frame copy between different formats or sizes");
    if (auto checked = checkFrame(source); !checked)
        return checked;
    const FrameView destination = view();
    const PixelFormatInfo &format = *layout_.format;
    for (unsigned p = 0; p < format.numPlanes; ++p) {
        const size_t rowBytes = format.minStride(p, layout_.width);
        const unsigned rows = format.planeHeight(p, layout_.height);
        for (unsigned y = 0; y < rows; ++y)
            std::memcpy(destination.planes[p].data + size_t(y) * destination.planes[p].stride,
                        source.planes[p].data + size_t(y) * source.planes[p].stride, rowBytes);
    }
    return Ok{};
}

} // namespace overlayd
