// SPDX-License-Identifier: Apache-2.0
// MappedBuffer: one mmap'ed V4L2 buffer plane, unmapped by its destructor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include "base/result.h"
#include "drivers/v4l2/v4l2_syscalls.h"

namespace overlayd {

class MappedBuffer
{
public:
    MappedBuffer() = default;
    // Maps `length` bytes of the device at the driver's `offset` (VIDIOC_QUERYBUF's m.offset / m.mem_offset).
    static Result<MappedBuffer> map(Syscalls &syscalls, int fd, size_t length, uint32_t offset);

    MappedBuffer(MappedBuffer &&other) noexcept { *this = std::move(other); }
    MappedBuffer &operator=(MappedBuffer &&other) noexcept;
    MappedBuffer(const MappedBuffer &) = delete;
    MappedBuffer &operator=(const MappedBuffer &) = delete;
    ~MappedBuffer() { reset(); }

    uint8_t *data() const { return data_; }
    size_t length() const { return length_; }
    void reset();

private:
    MappedBuffer(Syscalls &syscalls, uint8_t *data, size_t length) : syscalls_(&syscalls), data_(data), length_(length)
    {}

    Syscalls *syscalls_ = nullptr;
    uint8_t *data_ = nullptr;
    size_t length_ = 0;
};

} // namespace overlayd
