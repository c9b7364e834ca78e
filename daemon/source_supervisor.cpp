// SPDX-License-Identifier: Apache-2.0
// SourceSupervisor: opening and closing the source, and the frame path while it streams; then a reload that changes
// the source, and the source while it is down.
#include "daemon/source_supervisor.h"

#include <cmath>
#include <cstdio>

#include "base/number_text.h"

namespace overlayd {

SourceSupervisor::SourceSupervisor(Logger &logger, const DaemonConfig &config, SourceFactory makeSource,
                                   Pipeline &pipeline, SceneControl &scene, HealthReporter &health, Timers timers,
                                   FrameHook onFrame, StopHook stop)
    : logger_(logger), config_(config), makeSource_(std::move(makeSource)), pipeline_(pipeline), scene_(scene),
      health_(health), timers_(timers), onFrame_(std::move(onFrame)), stop_(std::move(stop))
{}

Status SourceSupervisor::open()
{
    auto source = openStream(makeSource_, config_, scene_, pipeline_, /*sinksMustOpen=*/state_ == State::Idle);
    if (!source)
        return source.error();
    startStreaming(std::move(*source));
    return Ok{};
}

void SourceSupervisor::startStreaming(std::unique_ptr<FrameSource> source)
{
    source_ = std::move(source);
    logger_.notice(cat("streaming from ", source_->describe(), ": ", pipeline_.format().describe()));
    if (auto viewport = scene_.camera().buildViewport(pipeline_.format().width, pipeline_.format().height))
        if (const std::string scaling = scene_.camera().calibrationScaling(*viewport); !scaling.empty())
            logger_.info(scaling);
    watchSource();
    timers_.noSignal.disarm();
    timers_.retry.disarm();
    noSignal_.reset();
    waitReason_.clear();
    backoff_.reset();
    state_ = State::Streaming;
    armStallTimer();
    health_.streaming(pipeline_.format());
}

std::optional<std::chrono::nanoseconds> SourceSupervisor::stallTimeout() const
{
    double seconds = 0.0;
    if (config_.source.kind == SourceKind::V4l2)
        seconds = config_.source.v4l2.noSignalTimeoutSec;
    else if (config_.source.kind == SourceKind::Libcamera)
        seconds = config_.source.libcamera.noSignalTimeoutSec;
    if (seconds <= 0.0)
        return std::nullopt;
    return std::chrono::nanoseconds(int64_t(std::llround(seconds * 1e9)));
}

void SourceSupervisor::armStallTimer()
{
    // One timer, two jobs: it paces NO SIGNAL frames only while Waiting, so while Streaming it can watch for a stall.
    if (const auto timeout = stallTimeout())
        (void)timers_.noSignal.arm(*timeout);
}

// A device is read when its fd says a frame is ready; any other source is paced by a timer at its frame rate.
void SourceSupervisor::watchSource()
{
    if (source_->eventFd() < 0) {
        (void)timers_.pacing.arm(pacingPeriod(), pacingPeriod());
    } else if (loop_ && watchedSourceFd_ < 0) {
        watchedSourceFd_ = source_->eventFd();
        (void)loop_->add(watchedSourceFd_, [this] { onFrameReady(); });
    }
}

void SourceSupervisor::attachLoop(EventLoop *loop)
{
    loop_ = loop;
    if (loop_ && source_)
        watchSource();
}

void SourceSupervisor::close()
{
    if (loop_ && watchedSourceFd_ >= 0)
        loop_->remove(watchedSourceFd_);
    watchedSourceFd_ = -1;
    timers_.pacing.disarm();
    if (source_)
        source_->stop();
    source_.reset();
}

void SourceSupervisor::onFrameReady()
{
    // A paced source gets one frame per tick (a late loop skips ticks rather than bursting); a device fd is drained.
    const int budget = watchedSourceFd_ >= 0 ? 8 : 1;
    for (int i = 0; i < budget && state_ == State::Streaming; ++i) {
        auto frame = source_->nextFrame();
        if (!frame) {
            handleSourceError(frame.error());
            return;
        }
        pipeline_.process(std::move(*frame));
        health_.frameDelivered(pipeline_.format());
        if (i == 0)
            armStallTimer();
        onFrame_();
    }
}

void SourceSupervisor::handleSourceError(const Error &error)
{
    if (error.code == ErrorCode::TryAgain)
        return;
    if (error.code == ErrorCode::EndOfStream) {
        logger_.notice(cat("source ended after ", pipeline_.framesIn(), " frames"));
        stop_(0);
    } else if (isRetryable(error)) {
        enterWaiting(error);
    } else {
        logger_.error(cat("source: ", error.message));
        stop_(1);
    }
}

std::chrono::nanoseconds SourceSupervisor::pacingPeriod() const
{
    return std::chrono::nanoseconds(int64_t(std::llround(1e9 / pacingFps())));
}

double SourceSupervisor::pacingFps() const
{
    // fps 0 means "as fast as frames come", which only `render` does; a running daemon paces at a sane default.
    if (pipeline_.format().fps > 0)
        return pipeline_.format().fps;
    return config_.source.fps > 0 ? config_.source.fps : 30.0;
}

// SourceSupervisor during a reload that changes the source: the new stream is opened before anything is switched,
// beside the running one or, for the same device, in its place with the way back kept open.

Result<SourceSupervisor::Staged> SourceSupervisor::stage(const DaemonConfig &next, const SceneControl &nextScene)
{
    Staged staged;
    staged.closedRunning = source_ && mayShareDevice(config_.source, next.source);
    if (staged.closedRunning)
        close();
    OpenFailure failure;
    auto stream = startStream(makeSource_, next, nextScene, &failure);
    if (stream) {
        staged.stream = std::move(*stream);
        return staged;
    }
    std::string why = stream.error().message;
    if (failure.step == OpenStep::StartSource && why.find(failure.source) == std::string::npos)
        why = cat(failure.source, ": ", why);
    if (staged.closedRunning)
        if (auto back = reopenRunning(); !back)
            why += cat("; the running source did not open again either: ", back.error().message);
    return makeError(stream.error().code, why);
}

void SourceSupervisor::adopt(Staged staged)
{
    close();
    startStreaming(runStream(std::move(staged.stream), scene_, pipeline_));
}

void SourceSupervisor::discard(Staged staged)
{
    if (staged.stream.source)
        staged.stream.source->stop();
    staged.stream = {};
    if (staged.closedRunning)
        (void)reopenRunning();
}

Status SourceSupervisor::reopenRunning()
{
    auto opened = open();
    if (!opened)
        enterWaiting(opened.error());
    return opened;
}

// SourceSupervisor while the source is down: back-off retries, NO SIGNAL frames, and what systemd is told meanwhile.

namespace {

std::string seconds(std::chrono::milliseconds delay)
{
    return shortNumber(double(delay.count()) / 1000.0) + " s";
}

} // namespace

bool SourceSupervisor::isRetryable(const Error &error) const
{
    // A camera that is unplugged, not yet plugged or misbehaving comes back by itself; a file that is missing or
    // malformed does not, except that a reload may fix it.
    if (error.code == ErrorCode::DeviceLost || error.code == ErrorCode::TryAgain)
        return true;
    const bool camera = config_.source.kind == SourceKind::V4l2 || config_.source.kind == SourceKind::Libcamera;
    return camera && (error.code == ErrorCode::NotFound || error.code == ErrorCode::Io);
}

void SourceSupervisor::enterWaiting(const Error &error)
{
    close();
    state_ = State::Waiting;
    if (error.message != waitReason_)
        logger_.warning(cat("source lost: ", error.message));
    waitReason_ = error.message;
    if (!pipeline_.format().format)
        (void)pipeline_.openSinks(configuredFormat());
    if (!noSignal_ || noSignal_->reason() != waitReason_)
        replaceNoSignal(pipeline_.format());
    (void)timers_.noSignal.arm(pacingPeriod(), pacingPeriod());
    scheduleRetry();
}

void SourceSupervisor::replaceNoSignal(const StreamFormat &format)
{
    noSignal_.reset();
    auto frame = NoSignalFrame::create(format, waitReason_);
    if (frame)
        noSignal_.emplace(std::move(*frame));
    else
        logger_.error(cat("NO SIGNAL frame: ", frame.error().message));
}

void SourceSupervisor::scheduleRetry()
{
    const auto delay = backoff_.next();
    (void)timers_.retry.arm(delay);
    logger_.debug(cat("retrying the source in ", seconds(delay)));
    // Before the first frame systemd is still waiting for READY=1: a camera that is late at boot must not fail the
    // unit's start-up timeout, so ask for time until the retry plus a margin.
    if (!health_.readySent())
        health_.notifier().extendTimeout(std::chrono::duration_cast<std::chrono::microseconds>(delay) +
                                         std::chrono::seconds(10));
    health_.waiting(cat("waiting for ",
                        config_.source.kind == SourceKind::V4l2 ? config_.source.v4l2.device
                        : config_.source.kind == SourceKind::Libcamera
                            ? "libcamera camera " + config_.source.libcamera.camera
                            : std::string("the source"),
                        ": ", waitReason_, ", retry in ", seconds(delay)));
}

void SourceSupervisor::onRetry()
{
    timers_.retry.consume();
    if (state_ != State::Waiting)
        return;
    auto opened = open();
    if (opened) {
        logger_.notice("source is back");
        return;
    }
    if (opened.error().message != waitReason_) {
        logger_.warning(cat("source still down: ", opened.error().message));
        waitReason_ = opened.error().message;
        replaceNoSignal(pipeline_.format());
    }
    scheduleRetry();
}

void SourceSupervisor::onNoSignalTick()
{
    timers_.noSignal.consume();
    if (state_ == State::Streaming && stallTimeout()) {
        const double seconds = std::chrono::duration<double>(*stallTimeout()).count();
        enterWaiting(Error{ErrorCode::DeviceLost, cat(describe(), ": no frame for ", seconds, " s")});
        return;
    }
    if (state_ != State::Waiting || !noSignal_)
        return;
    FrameMetadata metadata;
    metadata.sequence = noSignalSequence_++;
    metadata.timestamp = std::chrono::steady_clock::now().time_since_epoch();
    metadata.wallClock = std::chrono::system_clock::now();
    metadata.colorimetry = noSignal_->format().colorimetry;
    pipeline_.pushToSinks(noSignal_->view(), metadata);
}

StreamFormat SourceSupervisor::configuredFormat() const
{
    StreamFormat format;
    format.format = config_.source.pixelFormat;
    format.width = config_.source.width;
    format.height = config_.source.height;
    format.fps = config_.source.fps;
    format.colorimetry = config_.source.colorimetry.value_or(Colorimetry{});
    return format;
}

} // namespace overlayd
