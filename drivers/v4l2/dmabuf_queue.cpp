// DmabufQueue: REQBUFS, QBUF and DQBUF with V4L2_MEMORY_DMABUF.
#include "drivers/v4l2/dmabuf_queue.h"

#include <cerrno>
#include <string>

namespace overlayd::v4l2 {

Result<std::unique_ptr<DmabufQueue>> DmabufQueue::create(const VideoDevice &device, unsigned count)
{
    v4l2_requestbuffers request{};
    request.count = count;
    request.type = device.bufferType();
    request.memory = V4L2_MEMORY_DMABUF;
    if (const int r = device.ioctl(VIDIOC_REQBUFS, &request); r < 0)
        return ioctlError(device.describe() + ": VIDIOC_REQBUFS " + std::to_string(count) + " DMABUF buffers", r);
    std::unique_ptr<DmabufQueue> queue(new DmabufQueue(device, request.count));
    if (request.count == 0)
        return makeError(ErrorCode::Io, device.describe() + " granted no DMABUF buffers");
    return queue;
}

DmabufQueue::~DmabufQueue()
{
    v4l2_requestbuffers request{};
    request.type = device_.bufferType();
    request.memory = V4L2_MEMORY_DMABUF;
    (void)device_.ioctl(VIDIOC_REQBUFS, &request); // nothing to do if the device is already gone
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

} // namespace overlayd::v4l2
