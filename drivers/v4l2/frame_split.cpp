// SPDX-License-Identifier: Apache-2.0
// splitFrame: per-plane views of V4L2 buffers.
#include "drivers/v4l2/frame_split.h"

#include <algorithm>
#include <string>

namespace overlayd {

namespace {

FrameView separatePlanes(const PixelFormatInfo &info, const DeviceFormat &format, std::span<const PlaneMemory> memory)
{
    FrameView view{&info, format.width, format.height, {}};
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        const unsigned stride =
            format.planes[p].bytesPerLine ? format.planes[p].bytesPerLine : info.minStride(p, format.width);
        view.planes[p] = {memory[p].data, stride, memory[p].length};
    }
    return view;
}

Result<FrameView> contiguousPlanes(const PixelFormatInfo &info, const DeviceFormat &format, const PlaneMemory &memory)
{
    auto layout = makeFrameLayout(info, format.width, format.height, format.planes[0].bytesPerLine);
    if (!layout)
        return layout.error();
    FrameView view = layout->view(memory.data);
    for (unsigned p = 0; p < info.numPlanes; ++p) {
        // The driver may trim padding after the last row: the view ends where the buffer does.
        const size_t offset = layout->planes[p].offset;
        view.planes[p].size = offset >= memory.length ? 0 : std::min(view.planes[p].size, memory.length - offset);
    }
    return view;
}

} // namespace

Result<FrameView> splitFrame(const PixelFormatInfo &info, const DeviceFormat &format,
                             std::span<const PlaneMemory> memory)
{
    Result<FrameView> view =
        makeError(ErrorCode::Unsupported,
                  std::string(info.name) + " in " + std::to_string(memory.size()) + " memory planes is not supported");
    if (memory.size() == info.numPlanes)
        view = separatePlanes(info, format, memory);
    else if (memory.size() == 1)
        view = contiguousPlanes(info, format, memory[0]);
    if (!view)
        return view;
    if (auto checked = checkFrame(*view); !checked)
        return makeError(ErrorCode::Malformed, "driver buffer does not hold the format: " + checked.error().message);
    return view;
}

} // namespace overlayd
