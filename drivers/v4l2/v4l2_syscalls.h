// SPDX-License-Identifier: Apache-2.0
// The system calls the V4L2 code makes, behind an interface so that unit tests can stand in for the kernel.
#pragma once

#include <poll.h>
#include <sys/types.h>

#include <cstddef>
#include <string>
#include <vector>

#include "base/unique_fd.h"

namespace overlayd {

// Every call returns -errno on failure (as the raw system calls do), so callers never read the global errno and a
// fake can script any error. Modelled on sdbus-c++'s ISdBus seam.
class Syscalls : public FdCloser
{
public:
    virtual ~Syscalls() = default;

    virtual int open(const std::string &path, int flags) = 0; // fd or -errno
    int close(int fd) override = 0;
    virtual int ioctl(int fd, unsigned long request, void *argument) = 0; // 0 (or a non-negative value) or -errno
    // 0 and *address set, or -errno.
    virtual int mmap(size_t length, int prot, int flags, int fd, off_t offset, void **address) = 0;
    virtual int munmap(void *address, size_t length) = 0;
    virtual int poll(pollfd *fds, nfds_t count, int timeoutMs) = 0; // ready count or -errno
    // The /dev/video* nodes, sorted by number, for looking a device up by its card name.
    virtual std::vector<std::string> videoDevices() = 0;
};

// The kernel. Stateless, so one instance serves every device.
Syscalls &realSyscalls();

} // namespace overlayd
