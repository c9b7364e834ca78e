// SPDX-License-Identifier: Apache-2.0
// The real system calls behind the Syscalls seam.
#include "drivers/v4l2/v4l2_syscalls.h"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>

namespace overlayd {

namespace {

int orErrno(int result)
{
    return result < 0 ? -errno : result;
}

// "/dev/video10" sorts after "/dev/video9".
unsigned nodeNumber(const std::string &path)
{
    return unsigned(std::strtoul(path.c_str() + std::string("/dev/video").size(), nullptr, 10));
}

class RealSyscalls final : public Syscalls
{
public:
    int open(const std::string &path, int flags) override { return orErrno(::open(path.c_str(), flags)); }
    int close(int fd) override { return orErrno(::close(fd)); }
    int ioctl(int fd, unsigned long request, void *argument) override
    {
        return orErrno(::ioctl(fd, request, argument));
    }
    int mmap(size_t length, int prot, int flags, int fd, off_t offset, void **address) override
    {
        void *mapped = ::mmap(nullptr, length, prot, flags, fd, offset);
        if (mapped == MAP_FAILED)
            return -errno;
        *address = mapped;
        return 0;
    }
    int munmap(void *address, size_t length) override { return orErrno(::munmap(address, length)); }
    int poll(pollfd *fds, nfds_t count, int timeoutMs) override { return orErrno(::poll(fds, count, timeoutMs)); }
    std::vector<std::string> videoDevices() override;
};

std::vector<std::string> RealSyscalls::videoDevices()
{
    std::vector<std::string> nodes;
    std::error_code error;
    for (const auto &entry : std::filesystem::directory_iterator("/dev", error)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("video") && name.size() > 5 && std::isdigit(static_cast<unsigned char>(name[5])))
            nodes.push_back(entry.path().string());
    }
    std::sort(nodes.begin(), nodes.end(),
              [](const std::string &a, const std::string &b) { return nodeNumber(a) < nodeNumber(b); });
    return nodes;
}

} // namespace

Syscalls &realSyscalls()
{
    static RealSyscalls instance;
    return instance;
}

} // namespace overlayd
