// SPDX-License-Identifier: Apache-2.0
// DmabufQueue: REQBUFS, QBUF and DQBUF with V4L2_MEMORY_DMABUF.
#include "drivers/v4l2/dmabuf_queue.h"

#include <cerrno>
#include <string>

namespace overlayd {

Result<std::unique_ptr<DmabufQueue>> DmabufQueue::create(const VideoDevice &device, unsigned count)
{
    const Result<unsigned> granted = device.requestBuffers(count, V4L2_MEMORY_DMABUF);
    if (!granted)
        return granted.error();
    std::unique_ptr<DmabufQueue> queue(new DmabufQueue(device, *granted));
    if (*granted == 0)
        return makeError(ErrorCode::Io, device.describe() + " granted no DMABUF buffers");
    return queue;
}

DmabufQueue::~DmabufQueue()
{
    device_.releaseBuffers(V4L2_MEMORY_DMABUF);
}

Status DmabufQueue::queue(unsigned index, const std::array<DmabufPlane, 3> &planes, unsigned planeCount)
{
    v4l2_buffer buffer;
    std::array<v4l2_plane, VIDEO_MAX_PLANES> raw;
    prepareBuffer(buffer, raw, device_.bufferType(), V4L2_MEMORY_DMABUF, index);
    if (isMultiPlanar(device_.bufferType())) {
        buffer.length = planeCount;
        for (unsigned p = 0; p < planeCount; ++p) {
            raw[p].m.fd = planes[p].fd;
            raw[p].data_offset = planes[p].dataOffset;
            raw[p].bytesused = planes[p].bytesUsed;
            raw[p].length = planes[p].length;
        }
    } else {
        buffer.m.fd = planes[0].fd;
        buffer.bytesused = planes[0].bytesUsed;
        buffer.length = planes[0].length;
    }
    if (const int r = device_.ioctl(VIDIOC_QBUF, &buffer); r < 0)
        return ioctlError(device_.describe() + ": VIDIOC_QBUF " + std::to_string(index) + " (DMABUF)", r);
    return Ok{};
}

int DmabufQueue::dequeue(unsigned &index)
{
    v4l2_buffer buffer;
    std::array<v4l2_plane, VIDEO_MAX_PLANES> raw;
    if (const int r = device_.dequeue(V4L2_MEMORY_DMABUF, count_, buffer, raw); r < 0)
        return r;
    index = buffer.index;
    return 0;
}

} // namespace overlayd
