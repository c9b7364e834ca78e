// SPDX-License-Identifier: Apache-2.0
// MappedFrameBuffer: one libcamera FrameBuffer mapped once for CPU access, as a FrameView over its dmabufs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <libcamera/framebuffer.h>

#include "base/result.h"
#include "media/frame.h"

namespace overlayd {

class MappedFrameBuffer
{
public:
    // Maps every distinct dmabuf of the buffer's planes read-write (planes of one buffer often share a dmabuf at
    // different offsets); refuses planes that lie outside their dmabuf or are too small for the format.
    static Result<MappedFrameBuffer> map(const libcamera::FrameBuffer &buffer, const PixelFormatInfo &format,
                                         unsigned width, unsigned height, unsigned stride);

    MappedFrameBuffer(MappedFrameBuffer &&other) noexcept { *this = std::move(other); }
    MappedFrameBuffer &operator=(MappedFrameBuffer &&other) noexcept;
    MappedFrameBuffer(const MappedFrameBuffer &) = delete;
    MappedFrameBuffer &operator=(const MappedFrameBuffer &) = delete;
    ~MappedFrameBuffer() { unmap(); }

    // The frame, with each plane's dmabuf fd and offset set (a zero-copy sink queues them by DMABUF).
    const FrameView &view() const { return view_; }
    // DMA_BUF_IOCTL_SYNC around CPU access, so caches are coherent with the camera's DMA on every platform.
    void beginCpuAccess() const;
    void endCpuAccess() const;

private:
    MappedFrameBuffer() = default;
    void unmap();

    struct Mapping {
        int fd = -1;
        uint8_t *data = nullptr;
        size_t length = 0;
    };
    std::vector<Mapping> mappings_;
    FrameView view_{};
};

} // namespace overlayd
