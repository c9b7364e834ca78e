// SPDX-License-Identifier: Apache-2.0
// splitFrame: the FrameView of one V4L2 buffer, its planes located once from the driver's bytesperline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/result.h"
#include "drivers/v4l2/device_format.h"
#include "media/frame.h"

namespace overlayd {

struct PlaneMemory {
    uint8_t *data = nullptr;
    size_t length = 0;
};

// One memory plane per format plane (multi-planar API, NV12M): each plane keeps its own bytesperline. One memory
// plane holding a multi-plane format (single-planar API, or NV12 under the multi-planar API): the planes follow
// each other, with strides derived from plane 0's bytesperline as V4L2 defines them. Refuses buffers too small for
// the format.
Result<FrameView> splitFrame(const PixelFormatInfo &info, const DeviceFormat &format,
                             std::span<const PlaneMemory> memory);

} // namespace overlayd
