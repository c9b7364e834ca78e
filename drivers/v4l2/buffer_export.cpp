// BufferPool::exportDmabufs: VIDIOC_EXPBUF, and the per-plane fd and offset every frame view then carries.
#include "drivers/v4l2/buffer_pool.h"

#include <fcntl.h>

#include <string>

namespace overlayd {

Result<std::vector<UniqueFd>> BufferPool::exportDmabufs()
{
    std::vector<UniqueFd> fds;
    for (unsigned index = 0; index < buffers_.size(); ++index) {
        for (unsigned plane = 0; plane < buffers_[index].planes.size(); ++plane) {
            v4l2_exportbuffer request{};
            request.type = device_.bufferType();
            request.index = index;
            request.plane = plane;
            request.flags = O_CLOEXEC | O_RDWR;
            if (const int r = device_.ioctl(VIDIOC_EXPBUF, &request); r < 0) {
                for (Buffer &buffer : buffers_) // no view may keep an fd that is closed on return
                    for (PlaneView &view : buffer.view.planes)
                        view.dmabufFd = -1;
                return ioctlError(device_.describe() + ": VIDIOC_EXPBUF buffer " + std::to_string(index) + " plane " +
                                      std::to_string(plane),
                                  r);
            }
            fds.emplace_back(device_.syscalls(), request.fd);
            attachDmabuf(index, plane, request.fd);
        }
    }
    return fds;
}

// Every format plane that lies in this memory plane (all of them when one buffer holds NV12) gets its fd and its
// offset from the start of the buffer, so that an importer needs no layout knowledge of its own.
void BufferPool::attachDmabuf(unsigned index, unsigned memoryPlane, int fd)
{
    const MappedBuffer &memory = buffers_[index].planes[memoryPlane];
    for (PlaneView &plane : buffers_[index].view.planes) {
        if (plane.data >= memory.data() && plane.data < memory.data() + memory.length()) {
            plane.dmabufFd = fd;
            plane.dmabufOffset = size_t(plane.data - memory.data());
        }
    }
}

} // namespace overlayd