// SPDX-License-Identifier: Apache-2.0
// MappedBuffer: mapping, moves and unmapping.
#include "drivers/v4l2/mapped_buffer.h"

#include <sys/mman.h>

#include <cstring>
#include <string>
#include <utility>

namespace overlayd {

Result<MappedBuffer> MappedBuffer::map(Syscalls &syscalls, int fd, size_t length, uint32_t offset)
{
    void *address = nullptr;
    const int result = syscalls.mmap(length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, off_t(offset), &address);
    if (result < 0)
        return makeError(ErrorCode::Io,
                         "mmap of " + std::to_string(length) + " bytes failed: " + std::strerror(-result));
    return MappedBuffer(syscalls, static_cast<uint8_t *>(address), length);
}

MappedBuffer &MappedBuffer::operator=(MappedBuffer &&other) noexcept
{
    if (this != &other) {
        reset();
        syscalls_ = other.syscalls_;
        data_ = std::exchange(other.data_, nullptr);
        length_ = std::exchange(other.length_, 0);
    }
    return *this;
}

void MappedBuffer::reset()
{
    if (data_)
        syscalls_->munmap(std::exchange(data_, nullptr), std::exchange(length_, 0));
}

} // namespace overlayd
