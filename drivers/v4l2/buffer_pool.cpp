// SPDX-License-Identifier: Apache-2.0
// BufferPool: REQBUFS/QUERYBUF/mmap at creation, QBUF/DQBUF while streaming, and VIDIOC_EXPBUF for dmabuf export.
#include "drivers/v4l2/buffer_pool.h"

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <string>

#include "drivers/v4l2/frame_split.h"

namespace overlayd {

Result<std::unique_ptr<BufferPool>> BufferPool::create(const VideoDevice &device, unsigned count,
                                                       const DeviceFormat &format, const PixelFormatInfo *info)
{
    const Result<unsigned> granted = device.requestBuffers(count, V4L2_MEMORY_MMAP);
    if (!granted)
        return granted.error();
    std::unique_ptr<BufferPool> pool(new BufferPool(device));
    pool->buffers_.resize(*granted);
    if (*granted < 2)
        return makeError(ErrorCode::Io, device.describe() + " granted " + std::to_string(*granted) +
                                            " buffers; streaming needs at least 2");
    for (unsigned i = 0; i < *granted; ++i) {
        if (auto mapped = pool->mapBuffer(i, format, info); !mapped)
            return mapped.error();
    }
    return pool;
}

Status BufferPool::mapBuffer(unsigned index, const DeviceFormat &format, const PixelFormatInfo *info)
{
    v4l2_buffer buffer;
    std::array<v4l2_plane, VIDEO_MAX_PLANES> planes;
    prepareBuffer(buffer, planes, device_.bufferType(), V4L2_MEMORY_MMAP, index);
    if (const int r = device_.ioctl(VIDIOC_QUERYBUF, &buffer); r < 0)
        return ioctlError(device_.describe() + ": VIDIOC_QUERYBUF " + std::to_string(index), r);
    const bool mplane = isMultiPlanar(device_.bufferType());
    const unsigned count = mplane ? std::min<unsigned>(buffer.length, 3) : 1;
    std::vector<PlaneMemory> memory;
    for (unsigned p = 0; p < count; ++p) {
        const size_t length = mplane ? planes[p].length : buffer.length;
        const uint32_t offset = mplane ? planes[p].m.mem_offset : buffer.m.offset;
        auto mapped = MappedBuffer::map(device_.syscalls(), device_.fd(), length, offset);
        if (!mapped)
            return mapped.error();
        memory.push_back({mapped->data(), mapped->length()});
        buffers_[index].planes.push_back(std::move(mapped.value()));
    }
    if (!info)
        return Ok{};
    auto view = splitFrame(*info, format, memory);
    if (!view)
        return view.error();
    buffers_[index].view = *view;
    return Ok{};
}

BufferPool::~BufferPool()
{
    buffers_.clear(); // unmapped first: the driver frees only buffers nobody maps
    device_.releaseBuffers(V4L2_MEMORY_MMAP);
}

PlaneMemory BufferPool::memory(unsigned index, unsigned plane) const
{
    const MappedBuffer &mapped = buffers_[index].planes[plane];
    return {mapped.data(), mapped.length()};
}

Status BufferPool::queue(unsigned index, const std::array<uint32_t, 3> &bytesUsed)
{
    v4l2_buffer buffer;
    std::array<v4l2_plane, VIDEO_MAX_PLANES> planes;
    prepareBuffer(buffer, planes, device_.bufferType(), V4L2_MEMORY_MMAP, index);
    if (isMultiPlanar(device_.bufferType())) {
        buffer.length = unsigned(buffers_[index].planes.size());
        for (unsigned p = 0; p < buffer.length; ++p)
            planes[p].bytesused = bytesUsed[p];
    } else {
        buffer.bytesused = bytesUsed[0];
    }
    if (const int r = device_.ioctl(VIDIOC_QBUF, &buffer); r < 0)
        return ioctlError(device_.describe() + ": VIDIOC_QBUF " + std::to_string(index), r);
    ++queued_;
    return Ok{};
}

int BufferPool::dequeue(Dequeued &out)
{
    v4l2_buffer buffer;
    std::array<v4l2_plane, VIDEO_MAX_PLANES> planes;
    if (const int r = device_.dequeue(V4L2_MEMORY_MMAP, unsigned(buffers_.size()), buffer, planes); r < 0)
        return r;
    --queued_;
    out = {buffer.index,
           buffer.sequence,
           buffer.flags,
           std::chrono::seconds(buffer.timestamp.tv_sec) + std::chrono::microseconds(buffer.timestamp.tv_usec),
           {}};
    const bool mplane = isMultiPlanar(device_.bufferType());
    for (unsigned p = 0; p < (mplane ? std::min<unsigned>(buffer.length, 3) : 1); ++p) {
        out.bytesUsed[p] = mplane ? planes[p].bytesused : buffer.bytesused;
        out.dataOffset[p] = mplane ? planes[p].data_offset : 0;
    }
    return 0;
}

// BufferPool::exportDmabufs: VIDIOC_EXPBUF, and the per-plane fd and offset every frame view then carries.

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
