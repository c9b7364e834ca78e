// SPDX-License-Identifier: Apache-2.0
// SinkWorker: the queue, the drop policy and the worker thread.
#include "daemon/sink_worker.h"

#include <algorithm>

#include "control/status_report.h"

namespace overlayd {

SinkWorker::SinkWorker(std::unique_ptr<FrameSink> sink, const SinkOptions &options, Logger &logger, bool lossless)
    : sink_(std::move(sink)), options_(options), logger_(logger), lossless_(lossless)
{}

SinkWorker::~SinkWorker()
{
    if (auto status = close(); !status)
        logger_.error(cat(describe(), ": ", status.error().message));
}

Status SinkWorker::open(const StreamFormat &format)
{
    if (auto closed = close(); !closed)
        return closed;
    if (!format.format)
        return makeError(ErrorCode::InvalidArgument, "frame buffer needs a pixel format");
    // Checked here so that a copy never meets a format it cannot hold; the frames themselves come later.
    if (auto layout = makeFrameLayout(*format.format, format.width, format.height, format.stride); !layout)
        return layout.error();
    if (auto opened = sink_->open(format); !opened)
        return opened;
    format_ = format;
    inline_ = sink_->writesInline();
    slots_.clear();
    slots_.resize(inline_ ? 0 : std::max(1u, options_.queueDepth) + 1);
    created_ = 0;
    queued_.reset(slots_.size());
    free_.clear();
    free_.reserve(slots_.size());
    stopping_ = false;
    open_ = true;
    if (!inline_)
        thread_ = std::thread(&SinkWorker::threadMain, this);
    return Ok{};
}

std::optional<size_t> SinkWorker::takeFreeSlot(std::unique_lock<std::mutex> &lock)
{
    if (lossless_)
        slotFree_.wait(lock, [this] { return !free_.empty() || created_ < slots_.size(); });
    if (!free_.empty()) {
        const size_t slot = free_.back();
        free_.pop_back();
        return slot;
    }
    if (created_ < slots_.size())
        return created_++;
    // Every slot is queued or being written: the policy decides which frame is lost.
    ++counters_.dropped;
    if (options_.dropPolicy == DropPolicy::DropNewest || queued_.empty())
        return std::nullopt;
    const size_t oldest = queued_.front();
    queued_.pop_front();
    return oldest;
}

void SinkWorker::push(const FrameView &frame, const FrameMetadata &metadata)
{
    if (!isOpen())
        return;
    if (inline_) {
        writeInline([&] { return sink_->write(frame, metadata); }, false);
        return;
    }
    std::unique_lock lock(mutex_);
    const std::optional<size_t> slot = takeFreeSlot(lock);
    if (!slot)
        return;
    // The copy runs unlocked: the worker never touches a slot that is neither queued nor being written.
    lock.unlock();
    Slot &target = slots_[*slot];
    target.lease.reset(); // a dropped oldest frame may have been a reference
    if (!target.buffer)
        target.buffer = FrameBuffer::allocate(format_).value(); // the format was checked by open()
    const Status copied = target.buffer->copyFrom(frame);
    target.metadata = metadata;
    lock.lock();
    if (!copied) {
        free_.push_back(*slot);
        ++counters_.failed;
        lock.unlock();
        logger_.error(cat(describe(), ": ", copied.error().message));
        return;
    }
    queued_.push_back(*slot);
    wake_.notify_one();
}

void SinkWorker::push(const std::shared_ptr<const FrameLease> &lease)
{
    if (!isOpen())
        return;
    if (!sink_->takesLease(lease->view())) {
        push(lease->view(), lease->metadata());
        return;
    }
    if (inline_) { // the encoded stream: it hands the reference to the encoder at once, so no queue of ours
        writeInline([&] { return sink_->writeLease(lease); }, true);
        return;
    }
    std::unique_lock lock(mutex_);
    const std::optional<size_t> slot = takeFreeSlot(lock);
    if (!slot)
        return;
    // A dropped oldest frame's reference goes here, which may give its buffer back to the source.
    slots_[*slot].lease = lease;
    slots_[*slot].metadata = lease->metadata();
    queued_.push_back(*slot);
    wake_.notify_one();
}

void SinkWorker::threadMain()
{
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stopping_ || !queued_.empty(); });
        if (queued_.empty())
            return; // stopping, and everything queued was written
        const size_t slot = queued_.front();
        queued_.pop_front();
        lock.unlock();
        const auto start = std::chrono::steady_clock::now();
        Slot &item = slots_[slot];
        const bool leased = item.lease != nullptr;
        const Status written =
            leased ? sink_->writeLease(std::move(item.lease)) : sink_->write(item.buffer->view(), item.metadata);
        const auto elapsed = std::chrono::steady_clock::now() - start;
        if (!written)
            logger_.error(cat(describe(), ": ", written.error().message));
        lock.lock();
        count(written, elapsed, leased);
        free_.push_back(slot);
        slotFree_.notify_one();
    }
}

template<typename Write>
void SinkWorker::writeInline(const Write &write, bool leased)
{
    const auto start = std::chrono::steady_clock::now();
    const Status written = write();
    const auto elapsed = std::chrono::steady_clock::now() - start;
    if (!written)
        logger_.error(cat(describe(), ": ", written.error().message));
    std::lock_guard lock(mutex_);
    count(written, elapsed, leased);
}

void SinkWorker::count(const Status &written, std::chrono::steady_clock::duration elapsed, bool leased)
{
    counters_.writeTime += elapsed;
    ++(written ? counters_.written : counters_.failed);
    counters_.zeroCopy += written && leased;
}

Status SinkWorker::close()
{
    if (!open_)
        return Ok{};
    if (thread_.joinable()) {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_one();
        thread_.join();
    }
    open_ = false;
    for (Slot &slot : slots_)
        slot.lease.reset();
    return sink_->close();
}

SinkCounters SinkWorker::counters() const
{
    std::lock_guard lock(mutex_);
    return counters_;
}

size_t SinkWorker::allocatedFrames() const
{
    std::lock_guard lock(mutex_);
    size_t frames = 0;
    for (const Slot &slot : slots_)
        frames += slot.buffer.has_value();
    return frames;
}

void SinkWorker::report(StatusReport &report) const
{
    const SinkCounters counters = this->counters();
    // The config's name (or sink[N]) is the sink's identity: describe() changes as it writes ("null (66 frames)").
    const std::string &name = options().name;
    report.add("sinks", {{"name", name},
                         {"describe", describe()},
                         {"written", counters.written},
                         {"dropped", counters.dropped},
                         {"failed", counters.failed}});
    const std::string label = StatusReport::label("sink", name);
    report.metric("overlayd_sink_frames_total", "counter", "Frames a sink wrote.", double(counters.written), label);
    report.metric("overlayd_sink_dropped_total", "counter", "Frames a sink's queue dropped.", double(counters.dropped),
                  label);
    report.metric("overlayd_sink_failed_total", "counter", "Frames a sink failed to write.", double(counters.failed),
                  label);
}

} // namespace overlayd
