// SPDX-License-Identifier: Apache-2.0
// The fake V4L2 kernel: the seam's calls (open, close, ioctl, mmap, munmap, poll) over the fake devices.
#include "fake_v4l2.h"

#include <fcntl.h>

#include <cerrno>

namespace overlayd::test {

FakeDevice &FakeSyscalls::add(const std::string &path, const std::vector<std::string> &aliases)
{
    auto device = std::make_shared<FakeDevice>();
    device->dmabufBytes = [this](int fd) {
        return dmabufBytes(fd);
    };
    devices_[path] = device;
    present_[path] = true;
    nodes_.push_back(path);
    for (const std::string &alias : aliases) {
        devices_[alias] = device;
        present_[alias] = true;
    }
    return *device;
}

int FakeSyscalls::open(const std::string &path, int)
{
    auto found = devices_.find(path);
    if (found == devices_.end())
        return -ENOENT;
    if (!present_[path])
        return -ENODEV;
    fds_[nextFd_] = found->second;
    return nextFd_++;
}

int FakeSyscalls::close(int fd)
{
    return fds_.erase(fd) || dmabufs_.erase(fd) ? 0 : -EBADF;
}

int FakeSyscalls::ioctl(int fd, unsigned long request, void *argument)
{
    auto found = fds_.find(fd);
    if (found == fds_.end())
        return -EBADF;
    if (request == VIDIOC_EXPBUF)
        return exportBuffer(*found->second, found->second, *static_cast<v4l2_exportbuffer *>(argument));
    return found->second->ioctl(request, argument);
}

// As vb2 does: only MMAP buffers of the queue's type, a new fd per call; flags other than O_CLOEXEC and the access
// mode are refused.
int FakeSyscalls::exportBuffer(FakeDevice &device, const std::shared_ptr<FakeDevice> &owner, v4l2_exportbuffer &request)
{
    if (device.expbufError)
        return device.expbufError;
    if (request.type != device.bufferType || device.memory != V4L2_MEMORY_MMAP ||
        request.index >= device.buffers.size() || request.plane >= device.buffers[request.index].planes.size() ||
        (request.flags & ~(O_CLOEXEC | O_ACCMODE)))
        return -EINVAL;
    request.fd = nextFd_++;
    dmabufs_[request.fd] = {owner, request.index, request.plane};
    return 0;
}

std::vector<uint8_t> *FakeSyscalls::dmabufBytes(int fd)
{
    auto found = dmabufs_.find(fd);
    if (found == dmabufs_.end())
        return nullptr;
    FakeDevice &device = *found->second.device;
    if (found->second.index >= device.buffers.size() ||
        found->second.plane >= device.buffers[found->second.index].planes.size())
        return nullptr; // the exporter freed its buffers (a real dmabuf would keep them alive)
    return &device.buffers[found->second.index].planes[found->second.plane];
}

int FakeSyscalls::mmap(size_t length, int, int, int fd, off_t offset, void **address)
{
    auto found = fds_.find(fd);
    if (found == fds_.end())
        return -EBADF;
    FakeDevice &device = *found->second;
    const unsigned index = unsigned(offset >> 12) / 4, plane = unsigned(offset >> 12) % 4;
    if (offset % 4096 != 0 || index >= device.buffers.size() || plane >= device.buffers[index].planes.size() ||
        length != device.buffers[index].planes[plane].size())
        return -EINVAL;
    *address = device.buffers[index].planes[plane].data();
    maps_[*address] = found->second;
    ++device.mapped;
    ++mappings_;
    return 0;
}

int FakeSyscalls::munmap(void *address, size_t)
{
    auto found = maps_.find(address);
    if (found == maps_.end())
        return -EINVAL;
    --found->second->mapped;
    --mappings_;
    maps_.erase(found);
    return 0;
}

int FakeSyscalls::poll(pollfd *fds, nfds_t count, int)
{
    int ready = 0;
    for (nfds_t i = 0; i < count; ++i) {
        auto found = fds_.find(fds[i].fd);
        fds[i].revents = found == fds_.end() ? POLLNVAL : found->second->pollEvents;
        ready += fds[i].revents != 0;
    }
    return ready;
}

std::vector<std::string> FakeSyscalls::videoDevices()
{
    return nodes_;
}

} // namespace overlayd::test
