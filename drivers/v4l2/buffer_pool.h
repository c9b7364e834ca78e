// SPDX-License-Identifier: Apache-2.0
// BufferPool: a device's MMAP buffers, requested, mapped, queued and dequeued.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "base/unique_fd.h"
#include "drivers/v4l2/frame_split.h"
#include "drivers/v4l2/mapped_buffer.h"
#include "drivers/v4l2/video_device.h"
#include "media/frame.h"

namespace overlayd {

struct Dequeued {
    unsigned index = 0;
    uint32_t sequence = 0;
    uint32_t flags = 0;
    std::chrono::nanoseconds timestamp{0};
    std::array<uint32_t, 3> bytesUsed{};
    std::array<uint32_t, 3> dataOffset{}; // multi-planar: where the plane's data starts (vivid uses it)
};

class BufferPool
{
public:
    // VIDIOC_REQBUFS `count` MMAP buffers (the driver may grant another count), VIDIOC_QUERYBUF and map each.
    // With `info`, each buffer's FrameView is built here, once; compressed formats pass nullptr.
    static Result<std::unique_ptr<BufferPool>> create(const VideoDevice &device, unsigned count,
                                                      const DeviceFormat &format, const PixelFormatInfo *info);
    // Unmaps, then frees the driver's buffers (VIDIOC_REQBUFS 0). Stream off first.
    ~BufferPool();
    BufferPool(const BufferPool &) = delete;
    BufferPool &operator=(const BufferPool &) = delete;

    unsigned size() const { return unsigned(buffers_.size()); }
    unsigned memoryPlaneCount() const { return buffers_.empty() ? 0 : unsigned(buffers_[0].planes.size()); }
    unsigned queuedCount() const { return queued_; }
    const FrameView &view(unsigned index) const { return buffers_[index].view; }
    PlaneMemory memory(unsigned index, unsigned plane) const;

    // VIDIOC_EXPBUF of every buffer's memory planes (O_CLOEXEC): the views then carry each plane's dmabuf fd and
    // offset. The fds are the caller's to keep open while frames are out (exportDmabufs).
    Result<std::vector<UniqueFd>> exportDmabufs();

    // VIDIOC_QBUF; an output buffer carries bytesUsed per plane.
    Status queue(unsigned index, const std::array<uint32_t, 3> &bytesUsed = {});
    // VIDIOC_DQBUF, non-blocking: 0, or -errno (-EAGAIN: nothing ready).
    int dequeue(Dequeued &out);

private:
    struct Buffer {
        std::vector<MappedBuffer> planes;
        FrameView view{};
    };

    explicit BufferPool(const VideoDevice &device) : device_(device) {}
    Status mapBuffer(unsigned index, const DeviceFormat &format, const PixelFormatInfo *info);
    void attachDmabuf(unsigned index, unsigned memoryPlane, int fd);

    const VideoDevice &device_;
    std::vector<Buffer> buffers_;
    unsigned queued_ = 0;
};

} // namespace overlayd
