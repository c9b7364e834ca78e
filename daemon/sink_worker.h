// SinkWorker: one sink on its own thread behind a bounded queue of pooled frame copies (or, for a zero-copy sink,
// references to the source's buffers), so a slow sink never stalls the source; when the queue is full the sink's
// drop policy applies and drops are counted.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "base/logger.h"
#include "drivers/sink_options.h"
#include "media/frame_buffer.h"

namespace overlayd {

struct SinkCounters {
    uint64_t written = 0;                  // frames the sink accepted
    uint64_t dropped = 0;                  // frames the drop policy discarded
    uint64_t failed = 0;                   // frames the sink refused (write errors)
    std::chrono::nanoseconds writeTime{0}; // total time inside FrameSink::write
    uint64_t zeroCopy = 0;                 // of `written`: frames the sink took as leases (FrameSink::writeLease)
};

class SinkWorker
{
public:
    // lossless: push() waits for room instead of dropping (`overlayd render` must write every frame).
    SinkWorker(std::unique_ptr<FrameSink> sink, const SinkOptions &options, Logger &logger, bool lossless = false);
    ~SinkWorker();
    SinkWorker(const SinkWorker &) = delete;
    SinkWorker &operator=(const SinkWorker &) = delete;

    // Opens the sink for a stream and starts the thread; the pool holds queueDepth + 1 frames (one being written).
    Status open(const StreamFormat &format);
    // Copies the frame into a pooled buffer and queues it. Never blocks unless lossless.
    void push(const FrameView &frame, const FrameMetadata &metadata);
    // A source's frame: queued as a reference when the sink takes it (zero copy), else copied as above. The copy
    // happens here, on the caller's thread: the worker thread never reads a lease's mapped bytes.
    void push(const std::shared_ptr<const FrameLease> &lease);
    // Writes what is queued, stops the thread and closes the sink. Safe to call twice.
    Status close();

    bool isOpen() const { return thread_.joinable(); }
    const SinkOptions &options() const { return options_; }
    std::string describe() const { return sink_->describe(); }
    SinkCounters counters() const;

private:
    struct Slot {
        FrameBuffer buffer;
        FrameMetadata metadata;
        std::shared_ptr<const FrameLease> lease; // set: write this instead of the buffer
    };

    void threadMain();
    std::optional<size_t> takeFreeSlot(std::unique_lock<std::mutex> &lock);

    std::unique_ptr<FrameSink> sink_;
    SinkOptions options_;
    Logger &logger_;
    bool lossless_;

    std::vector<Slot> slots_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;     // the worker: a frame was queued, or stop
    std::condition_variable slotFree_; // a lossless push: a slot came back
    std::deque<size_t> queued_;        // slot indices, oldest first
    std::vector<size_t> free_;
    bool stopping_ = false;
    SinkCounters counters_;
    std::thread thread_;
};

} // namespace overlayd
