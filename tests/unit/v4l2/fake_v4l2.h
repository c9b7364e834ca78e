// SPDX-License-Identifier: Apache-2.0
// A fake V4L2 kernel behind the Syscalls seam: devices with scripted formats, buffers, frames and errors.
#pragma once

#include <linux/videodev2.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "drivers/v4l2/v4l2_syscalls.h"

namespace overlayd::test {

struct FakeFormat {
    uint32_t fourcc = 0;
    std::vector<std::pair<unsigned, unsigned>> sizes; // discrete sizes
    std::vector<double> rates;                        // discrete rates at every size
};

// One video node. Behaves as the V4L2 spec says a driver does, including the checks that catch misuse (QBUF
// of a buffer already queued, mmap of an unknown offset, a multi-planar QBUF without its plane array).
class FakeDevice
{
public:
    std::string card = "Fake Cam";
    uint32_t bufferType = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    std::vector<FakeFormat> formats;
    std::array<unsigned, 3> padding{}; // bytes the driver adds to each plane's minimum bytesperline
    uint32_t colorspace = V4L2_COLORSPACE_SMPTE170M, ycbcrEnc = 0, quantization = 0;
    std::array<uint32_t, 3> dataOffset{}; // multi-planar capture: reported by DQBUF per plane
    bool consumeOutput = true;            // output: a queued buffer is read at once and comes back done
    int expbufError = 0;                  // VIDIOC_EXPBUF fails with this when set (vb2: -EINVAL, not exportable)
    bool importsDmabuf = true;            // REQBUFS with V4L2_MEMORY_DMABUF is refused (-EINVAL) when false

    // What the driver holds now.
    v4l2_format format{};
    double fps = 0.0;
    bool streaming = false;
    struct Buffer {
        std::vector<std::vector<uint8_t>> planes;
        bool queued = false;
        std::array<uint32_t, 3> bytesUsed{};
        uint32_t sequence = 0, flags = 0;
        timeval timestamp{};
        std::array<int, 3> dmabufFds{-1, -1, -1}; // DMABUF queue: what the last QBUF imported
        std::array<uint32_t, 3> dataOffset{};
    };
    uint32_t memory = V4L2_MEMORY_MMAP; // of the current buffers
    std::vector<Buffer> buffers;
    std::deque<unsigned> queued, done;

    // Scripted answers to the next DQBUFs (-EINTR, -ENODEV, ...), before any real answer.
    std::deque<int> dqbufErrors;
    int qbufError = 0;    // every QBUF fails with this when set
    short pollEvents = 0; // what poll() reports
    unsigned dqbufCalls = 0, qbufCalls = 0, reqbufsZero = 0;
    unsigned mapped = 0;                                    // live mappings of this device's buffers
    std::vector<std::vector<std::vector<uint8_t>>> written; // output: the planes of every consumed buffer
    // DMABUF import: the bytes of an exported fd (set by FakeSyscalls), nullptr if it is no live dmabuf.
    std::function<std::vector<uint8_t> *(int fd)> dmabufBytes;

    // Capture: fills the oldest queued buffer and marks it done (bytesUsed = plane sizes unless fill changes
    // them). False if no buffer is queued.
    bool produce(uint32_t sequence, std::chrono::microseconds timestamp, const std::function<void(Buffer &)> &fill = {},
                 uint32_t flags = 0);

    // Output with consumeOutput = false: the oldest queued buffer is read now and comes back done.
    bool consume();

    int ioctl(unsigned long request, void *argument);

private:
    int setFormat(v4l2_format &f);
    int requestBuffers(v4l2_requestbuffers &r);
    int queryBuffer(v4l2_buffer &b);
    int queueBuffer(v4l2_buffer &b);
    int dequeueBuffer(v4l2_buffer &b);
    int importDmabufs(Buffer &buffer, const v4l2_buffer &b);
    void record(const Buffer &buffer);
    int enumSizes(v4l2_frmsizeenum &s) const;
    int enumIntervals(v4l2_frmivalenum &i) const;
    int parm(v4l2_streamparm &p, bool set);
    bool output() const;
    bool multiPlanar() const;
    unsigned memoryPlanes() const;
    uint32_t planeLength(unsigned plane) const;
};

class FakeSyscalls final : public Syscalls
{
public:
    // Adds a node; `aliases` are further paths to it (a /dev/v4l/by-id link).
    FakeDevice &add(const std::string &path, const std::vector<std::string> &aliases = {});
    void unplug(const std::string &path) { present_[path] = false; }

    int open(const std::string &path, int flags) override;
    int close(int fd) override;
    int ioctl(int fd, unsigned long request, void *argument) override;
    int mmap(size_t length, int prot, int flags, int fd, off_t offset, void **address) override;
    int munmap(void *address, size_t length) override;
    int poll(pollfd *fds, nfds_t count, int timeoutMs) override;
    std::vector<std::string> videoDevices() override;

    unsigned openFds() const { return unsigned(fds_.size() + dmabufs_.size()); }
    unsigned openDmabufs() const { return unsigned(dmabufs_.size()); }
    unsigned mappings() const { return mappings_; }

private:
    struct Dmabuf {
        std::shared_ptr<FakeDevice> device;
        unsigned index = 0, plane = 0;
    };
    int exportBuffer(FakeDevice &device, const std::shared_ptr<FakeDevice> &owner, v4l2_exportbuffer &request);
    std::vector<uint8_t> *dmabufBytes(int fd);

    std::map<std::string, std::shared_ptr<FakeDevice>> devices_; // path or alias -> device
    std::map<std::string, bool> present_;
    std::vector<std::string> nodes_;
    std::map<int, std::shared_ptr<FakeDevice>> fds_;
    std::map<void *, std::shared_ptr<FakeDevice>> maps_;
    std::map<int, Dmabuf> dmabufs_; // exported fds
    int nextFd_ = 100;
    unsigned mappings_ = 0;
};

// The mmap offset the fake hands out for a buffer plane, page aligned as a driver's are.
inline uint32_t fakeOffset(unsigned index, unsigned plane)
{
    return (index * 4 + plane) << 12;
}

} // namespace overlayd::test
