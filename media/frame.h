// SPDX-License-Identifier: Apache-2.0
// Frame views: a non-owning description of one frame's planes, and the layout of planes in one buffer.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/result.h"
#include "media/pixel_format.h"

namespace overlayd {

// One plane as the consumer sees it; stride is V4L2's bytesperline and may exceed the visible row.
struct PlaneView {
    uint8_t *data = nullptr;
    unsigned stride = 0;
    size_t size = 0;
    // The dmabuf holding the plane and where in it the plane starts (data_offset included), for zero-copy sinks;
    // -1 unless the frame is a lease of a source that exported its buffers (VIDIOC_EXPBUF). The source owns the fd.
    int dmabufFd = -1;
    size_t dmabufOffset = 0;
};

// Per-plane pointers travel with the frame so that consumers never compute where a chroma plane starts.
struct FrameView {
    const PixelFormatInfo *format = nullptr;
    unsigned width = 0, height = 0;
    std::array<PlaneView, 3> planes{};
};

// Frames wider or taller than this are refused before anything is allocated (V4L2 drivers top out at 16384 too).
inline constexpr unsigned kMaxFrameDimension = 16384;
// And a frame a file declares (a Y4M header) is refused above this many bytes of samples, before anything is
// allocated: 16384 x 16384 at 4:2:0 would be 384 MiB a frame, four times over in the frame pool.
inline constexpr size_t kMaxFrameBytes = size_t(256) << 20;

struct PlaneLayout {
    size_t offset = 0;
    unsigned stride = 0;
    size_t size = 0;
};

// Planes one after another in one buffer, as a single-planar V4L2 buffer holds a multi-plane format.
struct FrameLayout {
    const PixelFormatInfo *format = nullptr;
    unsigned width = 0, height = 0;
    std::array<PlaneLayout, 3> planes{};
    size_t totalSize = 0;

    FrameView view(uint8_t *base) const;
};

// stride 0 packs rows tightly; otherwise it is plane 0's bytesperline and the other planes' strides scale with
// their bytes per group, as V4L2 defines them for single-planar buffers (YUV420: Cb/Cr stride = stride / 2).
Result<FrameLayout> makeFrameLayout(const PixelFormatInfo &format, unsigned width, unsigned height,
                                    unsigned stride = 0);

// Refuses a view whose planes are missing or too small for its format and size; cheap enough for every frame.
Status checkFrame(const FrameView &frame);

} // namespace overlayd
