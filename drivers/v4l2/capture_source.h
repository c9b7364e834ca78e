// SPDX-License-Identifier: Apache-2.0
// V4l2CaptureSource: a V4L2 capture device as a FrameSource (negotiation, MMAP streaming, leases, MJPEG).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/frame_source.h"
#include "drivers/source_options.h"
#include "drivers/v4l2/buffer_pool.h"
#include "drivers/v4l2/lease_hub.h"
#include "drivers/v4l2/mjpeg_decoder.h"
#include "drivers/v4l2/video_device.h"
#include "media/frame_buffer.h"
#include "media/sequence_counter.h"

namespace overlayd {

// Where the source's few log lines go (the adjustment line, once per distinct adjustment).
using LogFunction = std::function<void(const std::string &)>;

class V4l2CaptureSource final : public FrameSource
{
public:
    // Borrows `syscalls` (the kernel, or a fake in tests); nothing is opened until start().
    V4l2CaptureSource(Syscalls &syscalls, SourceOptions options, LogFunction log);
    ~V4l2CaptureSource() override;

    Result<StreamFormat> start() override;
    // Streams off and frees the buffers. Leases still out become no-ops when given back (from any thread) and
    // keep their dmabuf fds open, but their mapped bytes are gone: only a zero-copy sink may hold one past stop().
    void stop() override;
    int eventFd() const override { return device_ ? device_->fd() : -1; }
    Result<FrameLease> nextFrame() override;
    std::string describe() const override;

    // Frames lost since start(): gaps in the driver's sequence numbers, frames it marked corrupt, MJPEG frames that
    // did not decode.
    uint64_t droppedFrames() const { return dropped_; }
    // The last adjustment line ("asked ..., got ..."), empty when the request was valid.
    const std::string &adjustment() const { return adjustment_; }

private:
    Result<StreamFormat> negotiate();
    Result<DeviceFormat> applyFormat(uint32_t fourcc, unsigned width, unsigned height);
    Status startStreaming(const DeviceFormat &format);
    void noteAdjustment(const StreamFormat &got, uint32_t deviceFourcc);
    std::vector<UniqueFd> exportBuffers();
    Result<FrameLease> deliver(const Dequeued &buffer);
    Result<FrameLease> failDequeue(int negativeErrno);
    void requeue(unsigned index);

    Syscalls &syscalls_;
    SourceOptions options_;
    LogFunction log_;

    // Runtime state of one start() .. stop(); the pool is declared after the device it borrows.
    std::unique_ptr<VideoDevice> device_;
    std::unique_ptr<BufferPool> pool_;
    std::unique_ptr<MjpegDecoder> decoder_;
    std::vector<FrameBuffer> decoded_; // MJPEG: one decoded frame per V4L2 buffer
    StreamFormat stream_{};
    bool mjpeg_ = false;
    bool streaming_ = false;
    std::shared_ptr<LeaseHub> hub_; // shared with the leases; detached by stop()

    SequenceCounter sequence_;
    uint64_t dropped_ = 0, decodeFailures_ = 0;
    std::string adjustment_, lastLogged_;
    bool exportFailureLogged_ = false;
};

} // namespace overlayd
