// SPDX-License-Identifier: Apache-2.0
// SinkWorker: one sink on its own thread behind a bounded queue of pooled frame copies (or, for a zero-copy sink,
// references to the source's buffers), so a slow sink never stalls the source; when the queue is full the sink's
// drop policy applies and drops are counted. The pool's frames are allocated as the queue first needs them (a sink
// that keeps up holds one or two); a sink that writes inline (the null sink) gets the frame itself on the caller's
// thread and holds none.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "base/logger.h"
#include "control/status_reporter.h"
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

class SinkWorker final : public StatusReporter
{
public:
    // lossless: push() waits for room instead of dropping (`overlayd render` must write every frame).
    SinkWorker(std::unique_ptr<FrameSink> sink, const SinkOptions &options, Logger &logger, bool lossless = false);
    ~SinkWorker();
    SinkWorker(const SinkWorker &) = delete;
    SinkWorker &operator=(const SinkWorker &) = delete;

    // Opens the sink for a stream and starts the thread (none for an inline sink); the pool may grow to
    // queueDepth + 1 frames (one being written).
    Status open(const StreamFormat &format);
    // Copies the frame into a pooled buffer and queues it (an inline sink writes it here, uncopied). Never blocks
    // unless lossless.
    void push(const FrameView &frame, const FrameMetadata &metadata);
    // A source's frame: queued as a reference when the sink takes it (zero copy), else copied as above. The copy
    // happens here, on the caller's thread: the worker thread never reads a lease's mapped bytes.
    void push(const std::shared_ptr<const FrameLease> &lease);
    // Whether push(lease) would keep a reference to this frame instead of copying it.
    bool takesLease(const FrameView &frame) const { return isOpen() && sink_->takesLease(frame); }
    // Writes what is queued, stops the thread and closes the sink. Safe to call twice.
    Status close();

    bool isOpen() const { return open_; }
    // Frames the pool has allocated so far (for tests and the footprint figures).
    size_t allocatedFrames() const;
    const SinkOptions &options() const { return options_; }
    std::string describe() const { return sink_->describe(); }
    SinkCounters counters() const;
    // Its entry in /state's "sinks" and its samples in /metrics.
    void report(StatusReport &report) const override;

private:
    struct Slot {
        std::optional<FrameBuffer> buffer; // allocated by the first copy into this slot
        FrameMetadata metadata;
        std::shared_ptr<const FrameLease> lease; // set: write this instead of the buffer
    };

    void threadMain();
    // The sink's write() or writeLease() on the caller's thread, timed and counted. A template rather than a
    // std::function: the call's captures (three references) would not fit std::function's own storage, and the
    // frame path allocates nothing in the steady state (tests/unit/daemon/steady_allocation_test.cpp).
    template<typename Write>
    void writeInline(const Write &write, bool leased);
    // Counts one write of the sink's (the lock held).
    void count(const Status &written, std::chrono::steady_clock::duration elapsed, bool leased);
    std::optional<size_t> takeFreeSlot(std::unique_lock<std::mutex> &lock);

    std::unique_ptr<FrameSink> sink_;
    SinkOptions options_;
    Logger &logger_;
    bool lossless_;

    StreamFormat format_{};
    bool open_ = false;
    bool inline_ = false;
    // queueDepth + 1 entries from open() on, so a slot never moves while the worker writes it; `created_` of them
    // have been handed out at least once.
    std::vector<Slot> slots_;
    size_t created_ = 0;
    mutable std::mutex mutex_;
    std::condition_variable wake_;     // the worker: a frame was queued, or stop
    std::condition_variable slotFree_; // a lossless push: a slot came back
    // Slot indices, oldest first: a ring over fixed storage (a std::deque allocates a block every 64 frames).
    class SlotQueue
    {
    public:
        void reset(size_t capacity) { ring_.assign(capacity, 0), head_ = size_ = 0; }
        bool empty() const { return size_ == 0; }
        size_t front() const { return ring_[head_]; }
        void pop_front() { head_ = (head_ + 1) % ring_.size(), --size_; }
        void push_back(size_t slot) { ring_[(head_ + size_++) % ring_.size()] = slot; } // never more than slots

    private:
        std::vector<size_t> ring_;
        size_t head_ = 0, size_ = 0;
    };
    SlotQueue queued_;
    std::vector<size_t> free_;
    bool stopping_ = false;
    SinkCounters counters_;
    std::thread thread_;
};

} // namespace overlayd
