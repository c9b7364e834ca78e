// SPDX-License-Identifier: Apache-2.0
// MappedFrameBuffer: mmap of a libcamera buffer's dmabufs, and the sync ioctls around CPU access.
#include "drivers/libcamera/mapped_frame_buffer.h"

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include <linux/dma-buf.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace overlayd {

namespace {

void syncDmabuf(int fd, uint64_t flags)
{
    dma_buf_sync sync{flags | DMA_BUF_SYNC_RW};
    // EINTR: retried. Other errors (a heap that needs no sync) leave the data as it is: nothing to undo.
    while (::ioctl(fd, DMA_BUF_IOCTL_SYNC, &sync) < 0 && errno == EINTR) {
    }
}

} // namespace

Result<MappedFrameBuffer> MappedFrameBuffer::map(const libcamera::FrameBuffer &buffer, const PixelFormatInfo &format,
                                                 unsigned width, unsigned height, unsigned stride)
{
    auto layout = makeFrameLayout(format, width, height, stride);
    if (!layout)
        return layout.error();
    const auto &planes = buffer.planes();
    if (planes.empty() || planes.size() > 3)
        return makeError(ErrorCode::Malformed, "a libcamera buffer with " + std::to_string(planes.size()) + " planes");

    MappedFrameBuffer mapped;
    const auto mappingOf = [&](int fd) -> Result<const Mapping *> {
        for (const Mapping &m : mapped.mappings_) {
            if (m.fd == fd)
                return &m;
        }
        const off_t end = ::lseek(fd, 0, SEEK_END);
        if (end <= 0)
            return makeError(ErrorCode::Io, std::string("sizing a dmabuf: ") + std::strerror(errno));
        void *data = ::mmap(nullptr, size_t(end), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        if (data == MAP_FAILED)
            return makeError(ErrorCode::Io, std::string("mapping a dmabuf: ") + std::strerror(errno));
        mapped.mappings_.push_back({fd, static_cast<uint8_t *>(data), size_t(end)});
        return &mapped.mappings_.back();
    };

    mapped.mappings_.reserve(planes.size());
    FrameView view{&format, width, height, {}};
    for (unsigned p = 0; p < format.numPlanes; ++p) {
        // One libcamera plane per format plane; a buffer with fewer holds the rest after plane 0, packed as V4L2
        // single-planar buffers are.
        const bool own = p < planes.size();
        const libcamera::FrameBuffer::Plane &plane = planes[own ? p : 0];
        auto mapping = mappingOf(plane.fd.get());
        if (!mapping)
            return mapping.error();
        const size_t offset = size_t(plane.offset) + (own ? 0 : layout->planes[p].offset);
        const size_t size = own ? plane.length : layout->planes[p].size;
        if (plane.offset == libcamera::FrameBuffer::Plane::kInvalidOffset || offset + size > (*mapping)->length)
            return makeError(ErrorCode::Malformed, "libcamera plane " + std::to_string(p) + " lies outside its dmabuf");
        view.planes[p].data = (*mapping)->data + offset;
        view.planes[p].stride = layout->planes[p].stride;
        view.planes[p].size = size;
        view.planes[p].dmabufFd = plane.fd.get();
        view.planes[p].dmabufOffset = offset;
    }
    if (auto checked = checkFrame(view); !checked)
        return checked.error();
    mapped.view_ = view;
    return mapped;
}

MappedFrameBuffer &MappedFrameBuffer::operator=(MappedFrameBuffer &&other) noexcept
{
    if (this != &other) {
        unmap();
        mappings_ = std::move(other.mappings_);
        view_ = std::exchange(other.view_, FrameView{});
        other.mappings_.clear();
    }
    return *this;
}

void MappedFrameBuffer::beginCpuAccess() const
{
    for (const Mapping &m : mappings_)
        syncDmabuf(m.fd, DMA_BUF_SYNC_START);
}

void MappedFrameBuffer::endCpuAccess() const
{
    for (const Mapping &m : mappings_)
        syncDmabuf(m.fd, DMA_BUF_SYNC_END);
}

void MappedFrameBuffer::unmap()
{
    for (const Mapping &m : mappings_)
        ::munmap(m.data, m.length);
    mappings_.clear();
}

} // namespace overlayd
