// SPDX-License-Identifier: Apache-2.0
// V4l2OutputSink: writes the overlaid stream to a V4L2 output device (v4l2loopback, vivid's output node), by copy
// into MMAP buffers or, zero copy, by queueing the capture buffers themselves (DMABUF import).
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/frame_sink.h"
#include "drivers/sink_options.h"
#include "drivers/v4l2/buffer_pool.h"
#include "drivers/v4l2/dmabuf_queue.h"
#include "drivers/v4l2/video_device.h"

namespace overlayd {

class V4l2OutputSink final : public FrameSink
{
public:
    using LogFunction = std::function<void(const std::string &)>;

    // Borrows `syscalls`; the device is opened by open(). `log` gets the zero-copy decision and a summary.
    V4l2OutputSink(Syscalls &syscalls, SinkOptions options, LogFunction log = {})
        : syscalls_(syscalls), options_(std::move(options)), log_(std::move(log))
    {}
    ~V4l2OutputSink() override { (void)close(); }

    // Sets the device's output format to the stream's (refused formats and sizes are errors), decides copy or zero
    // copy (options.zeroCopy; "on" and impossible is a ConfigError naming why), sets up the buffers and streams.
    Status open(const StreamFormat &format) override;
    // Copies the frame into a free MMAP buffer and queues it. With no free buffer (the reader is slow) the frame
    // is dropped and counted: the pipeline never waits for the device. Frames without dmabuf fds (NO SIGNAL) take
    // this path in zero-copy mode too: the queue is switched to MMAP until the next lease.
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override;
    std::string describe() const override;

    // Zero copy: frames whose dmabuf planes sit where the output's format puts them (chooseMemory).
    bool takesLease(const FrameView &frame) const override;
    // Queues the lease's dmabufs (VIDIOC_QBUF m.fd) and keeps the reference until VIDIOC_DQBUF returns the buffer.
    Status writeLease(std::shared_ptr<const FrameLease> lease) override;

    bool zeroCopy() const { return zeroCopy_; }
    uint64_t droppedFrames() const { return dropped_; }
    uint64_t writtenFrames() const { return written_; }
    uint64_t zeroCopiedFrames() const { return zeroCopied_; }
    uint64_t heldLeases() const;

private:
    enum class Memory { None, Mmap, Dmabuf };
    struct Slot {
        std::shared_ptr<const FrameLease> lease; // held while the device has the buffer
        int lastFd = -1;                         // requeueing the same dmabuf lets vb2 skip re-importing it
    };
    // Where each format plane must lie in the output's memory planes, from the format the driver accepted.
    struct PlacedPlane {
        unsigned memoryPlane = 0;
        size_t offset = 0; // from the start of that memory plane's data
        unsigned stride = 0;
    };

    Status setFormat(const StreamFormat &format);
    void placePlanes(const PixelFormatInfo &info, unsigned width, unsigned height);
    std::string zeroCopyRefusal(const StreamFormat &format);
    Status chooseMemory(const StreamFormat &format);
    Status useMemory(Memory memory);
    Status reclaim();
    Status reclaimLeases();
    void releaseLeases();
    Status copyInto(unsigned index, const FrameView &frame);
    bool dmabufPlanes(const FrameView &frame, std::array<DmabufPlane, 3> &planes) const;
    std::optional<unsigned> takeLeaseSlot(int fd);
    void log(const std::string &line) const;

    Syscalls &syscalls_;
    SinkOptions options_;
    LogFunction log_;
    std::unique_ptr<VideoDevice> device_;
    // After the device they borrow; one of the two exists while open (a V4L2 queue has one memory type).
    std::unique_ptr<BufferPool> pool_;
    std::unique_ptr<DmabufQueue> dmabuf_;
    Memory memory_ = Memory::None;
    bool streaming_ = false; // open() succeeded: a memory switch streams off and on again
    DeviceFormat deviceFormat_{};
    StreamFormat stream_{};
    // Decided by open() and only read until close(): takesLease() runs on the pipeline's thread.
    std::atomic<bool> zeroCopy_ = false; // the sink thread clears it when the driver refuses a DMABUF QBUF
    unsigned leaseSlots_ = 0;            // output buffers that may hold leases: the capture keeps 2 of its own
    std::array<PlacedPlane, 3> placed_{};
    std::vector<unsigned> free_; // MMAP
    std::vector<Slot> slots_;    // DMABUF
    uint64_t dropped_ = 0, written_ = 0, zeroCopied_ = 0;
};

} // namespace overlayd
