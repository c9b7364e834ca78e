// SPDX-License-Identifier: Apache-2.0
// Pipeline: the per-frame path and its statistics; then the sinks during a reload.
#include "daemon/pipeline.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "base/number_text.h"

namespace overlayd {

namespace {

double millis(std::chrono::nanoseconds total, uint64_t count)
{
    return count ? std::chrono::duration<double, std::milli>(total).count() / double(count) : 0.0;
}

std::string fixed(double value, int decimals)
{
    return formatted("%.*f", decimals, value);
}

SinkCounters operator-(const SinkCounters &a, const SinkCounters &b)
{
    return {a.written - b.written, a.dropped - b.dropped, a.failed - b.failed, a.writeTime - b.writeTime,
            a.zeroCopy - b.zeroCopy};
}

} // namespace

std::string PipelineStats::describe() const
{
    const double seconds = std::chrono::duration<double>(period).count();
    const auto rate = [seconds](uint64_t frames) {
        return seconds > 0 ? double(frames) / seconds : 0.0;
    };
    std::string text = cat("in ", fixed(rate(framesIn), 1), " fps, blend ", fixed(millis(blendTime, framesIn), 2),
                           " ms, queue ", fixed(millis(pushTime, framesIn), 2), " ms");
    if (exposureUs)
        text += cat(", exposure ", *exposureUs, " us");
    if (analogueGain)
        text += cat(", gain ", fixed(*analogueGain, 2));
    for (const Sink &sink : sinks)
        text += cat("; ", sink.name, ": out ", fixed(rate(sink.counters.written), 1), " fps, ", sink.counters.dropped,
                    " dropped, ", sink.counters.failed, " failed, write ",
                    fixed(millis(sink.counters.writeTime, sink.counters.written + sink.counters.failed), 2), " ms",
                    sink.counters.zeroCopy ? cat(", ", sink.counters.zeroCopy, " zero-copy") : std::string());
    return text;
}

void Pipeline::setSinks(std::vector<std::unique_ptr<SinkWorker>> sinks)
{
    closeSinks();
    for (const auto &sink : sinks_)
        retiredDrops_ += sink->counters().dropped;
    sinks_ = std::move(sinks);
    lastCounters_.assign(sinks_.size(), SinkCounters{});
}

Status Pipeline::openSinks(const StreamFormat &format)
{
    format_ = format;
    Status result = Ok{};
    for (auto &sink : sinks_) {
        if (auto opened = sink->open(format); !opened) {
            logger_.error(cat(sink->describe(), ": cannot open for ", format.describe(), ": ", opened.error().message));
            if (result)
                result = opened;
        }
    }
    return result;
}

void Pipeline::closeSinks()
{
    for (auto &sink : sinks_)
        if (auto closed = sink->close(); !closed)
            logger_.error(cat(sink->describe(), ": ", closed.error().message));
}

void Pipeline::process(const FrameView &frame, const FrameMetadata &metadata)
{
    const auto start = std::chrono::steady_clock::now();
    if (!blend(frame, metadata))
        return;
    const auto blended = std::chrono::steady_clock::now();
    pushToSinks(frame, metadata);
    countFrame(metadata, start, blended);
}

void Pipeline::process(FrameLease lease)
{
    const auto start = std::chrono::steady_clock::now();
    if (!blend(lease.view(), lease.metadata()))
        return;
    const auto blended = std::chrono::steady_clock::now();
    // Shared only when a sink keeps a reference: the others copy (or write inline) before this returns, and the
    // lease goes back to the source right after, with no allocation for the frame.
    const bool referenced =
        std::any_of(sinks_.begin(), sinks_.end(), [&](const auto &sink) { return sink->takesLease(lease.view()); });
    if (!referenced) {
        pushToSinks(lease.view(), lease.metadata());
        countFrame(lease.metadata(), start, blended);
        return;
    }
    const auto shared = std::make_shared<const FrameLease>(std::move(lease));
    for (auto &sink : sinks_)
        sink->push(shared);
    countFrame(shared->metadata(), start, blended);
}

bool Pipeline::blend(const FrameView &frame, const FrameMetadata &metadata)
{
    // The privacy masks first: the raw tap (snapshots with raw=1) and every sink see the masked frame only, and a
    // frame that could not be masked goes nowhere.
    if (renderer_)
        if (auto masked = renderer_->applyMasks(frame); !masked) {
            logger_.error(cat("privacy masks: ", masked.error().message, "; the frame is dropped"));
            return false;
        }
    if (rawTap_)
        rawTap_(frame, metadata);
    if (!renderer_)
        return true;
    if (auto blended = renderer_->blend(frame, metadata, format_.fps); !blended)
        logger_.error(cat("overlay: ", blended.error().message));
    return true;
}

void Pipeline::countFrame(const FrameMetadata &metadata, std::chrono::steady_clock::time_point start,
                          std::chrono::steady_clock::time_point blended)
{
    lastExposureUs_ = metadata.exposureUs;
    lastAnalogueGain_ = metadata.analogueGain;
    blendTime_ += blended - start;
    pushTime_ += std::chrono::steady_clock::now() - blended;
    ++framesIn_;
    ++framesInTotal_;
}

void Pipeline::pushToSinks(const FrameView &frame, const FrameMetadata &metadata)
{
    for (auto &sink : sinks_)
        sink->push(frame, metadata);
}

PipelineStats Pipeline::takeStats()
{
    const auto now = std::chrono::steady_clock::now();
    PipelineStats stats;
    stats.period = now - lastStats_;
    stats.framesIn = framesIn_;
    stats.blendTime = blendTime_;
    stats.pushTime = pushTime_;
    stats.totalDrops = retiredDrops_;
    stats.exposureUs = lastExposureUs_;
    stats.analogueGain = lastAnalogueGain_;
    for (size_t i = 0; i < sinks_.size(); ++i) {
        const SinkCounters counters = sinks_[i]->counters();
        stats.sinks.push_back({sinks_[i]->describe(), counters - lastCounters_[i]});
        stats.totalDrops += counters.dropped;
        lastCounters_[i] = counters;
    }
    lastStats_ = now;
    framesIn_ = 0;
    blendTime_ = pushTime_ = {};
    return stats;
}

// Pipeline during a reload: the new sinks open before the running ones close, except where both write to one place.

namespace {

// Two sinks that write to one place (a file, a device, stdout, the HTTP feed) cannot both be open: the new one waits
// until the running one has closed.
bool sameOutput(const SinkWorker &a, const SinkWorker &b)
{
    return !a.options().path.empty() && a.options().path == b.options().path;
}

Status openFor(SinkWorker &sink, const StreamFormat &format)
{
    if (auto opened = sink.open(format); !opened)
        return makeError(opened.error().code,
                         cat(sink.describe(), ": cannot open for ", format.describe(), ": ", opened.error().message));
    return Ok{};
}

} // namespace

Status Pipeline::replaceSinks(std::vector<std::unique_ptr<SinkWorker>> sinks, const StreamFormat &format,
                              const KeepSink &keep)
{
    const auto kept = [&keep](const SinkWorker &sink) {
        return keep && keep(sink);
    };
    const auto takesOver = [this, &kept](const SinkWorker &sink) {
        return std::any_of(sinks_.begin(), sinks_.end(),
                           [&](const auto &running) { return !kept(*running) && sameOutput(*running, sink); });
    };
    const bool newFormat = format != format_;
    // Gives up: the new sinks close, and the running ones are open for the running format again (those closed, and
    // the kept ones that a new format re-opened).
    const auto refuse = [&](Status failed) {
        for (auto &each : sinks)
            (void)each->close();
        for (auto &running : sinks_)
            if (!running->isOpen() || (newFormat && kept(*running)))
                if (auto opened = openFor(*running, format_); !opened)
                    logger_.error(opened.error().message);
        return failed;
    };
    if (newFormat)
        for (auto &running : sinks_)
            if (kept(*running))
                if (auto opened = openFor(*running, format); !opened)
                    return refuse(opened);
    // First the sinks that write elsewhere, while the running ones still write; then, once those have written what
    // they hold and closed, the ones that take over their files and devices.
    for (const bool afterRunning : {false, true}) {
        if (afterRunning)
            for (auto &running : sinks_)
                if (!kept(*running))
                    if (auto closed = running->close(); !closed)
                        logger_.error(cat(running->describe(), ": ", closed.error().message));
        for (auto &sink : sinks) {
            if (takesOver(*sink) != afterRunning)
                continue;
            if (auto opened = openFor(*sink, format); !opened)
                return refuse(opened);
        }
    }
    // The kept sinks move over with their counters' last reading, so that the stats line goes on from it.
    std::vector<SinkCounters> lastCounters(sinks.size(), SinkCounters{});
    for (size_t i = 0; i < sinks_.size(); ++i)
        if (kept(*sinks_[i])) {
            sinks.push_back(std::move(sinks_[i]));
            lastCounters.push_back(lastCounters_[i]);
        }
    std::erase(sinks_, nullptr);
    setSinks(std::move(sinks));
    lastCounters_ = std::move(lastCounters);
    format_ = format;
    return Ok{};
}

Status Pipeline::reopenSinks(const StreamFormat &format)
{
    for (auto &sink : sinks_)
        if (auto opened = openFor(*sink, format); !opened) {
            restoreSinks();
            return opened;
        }
    format_ = format;
    return Ok{};
}

void Pipeline::restoreSinks()
{
    for (auto &sink : sinks_)
        if (auto opened = openFor(*sink, format_); !opened)
            logger_.error(opened.error().message);
}

} // namespace overlayd
