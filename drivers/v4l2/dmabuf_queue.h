// SPDX-License-Identifier: Apache-2.0
// DmabufQueue: an output device's V4L2_MEMORY_DMABUF queue: buffers that are other devices' dmabufs.
#pragma once

#include <array>
#include <memory>

#include "drivers/v4l2/buffer_pool.h"
#include "drivers/v4l2/video_device.h"

namespace overlayd {

// One memory plane of a queued buffer: the dmabuf, where the data starts in it, the bytes used counted from the
// start of the dmabuf (V4L2's multi-planar convention: data_offset included) and the dmabuf's usable length.
struct DmabufPlane {
    int fd = -1;
    uint32_t dataOffset = 0;
    uint32_t bytesUsed = 0;
    uint32_t length = 0;
};

class DmabufQueue
{
public:
    // VIDIOC_REQBUFS `count` DMABUF buffers; the driver may grant another count. Fails when the driver cannot
    // import dmabufs (EINVAL), which is how V4L2 says so.
    static Result<std::unique_ptr<DmabufQueue>> create(const VideoDevice &device, unsigned count);
    // Frees the driver's buffers (VIDIOC_REQBUFS 0), which drops its references to the dmabufs. Stream off first.
    ~DmabufQueue();
    DmabufQueue(const DmabufQueue &) = delete;
    DmabufQueue &operator=(const DmabufQueue &) = delete;

    unsigned size() const { return count_; }
    // VIDIOC_QBUF with m.fd (single-planar: the data must start at offset 0) or m.planes[i].m.fd.
    Status queue(unsigned index, const std::array<DmabufPlane, 3> &planes, unsigned planeCount);
    // VIDIOC_DQBUF, non-blocking: 0 and the index, or -errno (-EAGAIN: nothing done yet).
    int dequeue(unsigned &index);

private:
    DmabufQueue(const VideoDevice &device, unsigned count) : device_(device), count_(count) {}

    const VideoDevice &device_;
    unsigned count_;
};

} // namespace overlayd
