// V4l2OutputSink: writes the overlaid stream to a V4L2 output device (v4l2loopback, vivid's output node).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drivers/frame_sink.h"
#include "drivers/sink_options.h"
#include "drivers/v4l2/buffer_pool.h"
#include "drivers/v4l2/video_device.h"

namespace overlayd::v4l2 {

class V4l2OutputSink final : public FrameSink
{
public:
    // Borrows `syscalls`; the device is opened by open().
    V4l2OutputSink(Syscalls &syscalls, SinkOptions options) : syscalls_(syscalls), options_(std::move(options)) {}
    ~V4l2OutputSink() override { (void)close(); }

    // Sets the device's output format to the stream's (refused formats and sizes are errors), maps the buffers
    // and starts streaming.
    Status open(const StreamFormat &format) override;
    // Copies the frame into a free buffer and queues it. With no free buffer (the reader is slow) the frame is
    // dropped and counted: the pipeline never waits for the device.
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override;
    std::string describe() const override;

    uint64_t droppedFrames() const { return dropped_; }
    uint64_t writtenFrames() const { return written_; }

private:
    Status reclaim();
    Status copyInto(unsigned index, const FrameView &frame);

    Syscalls &syscalls_;
    SinkOptions options_;
    std::unique_ptr<VideoDevice> device_;
    std::unique_ptr<BufferPool> pool_; // after the device it borrows
    DeviceFormat deviceFormat_{};
    StreamFormat stream_{};
    std::vector<unsigned> free_;
    uint64_t dropped_ = 0, written_ = 0;
};

} // namespace overlayd::v4l2
