// SourceSupervisor: opening and closing the source, and the frame path while it streams.
#include "daemon/source_supervisor.h"

#include <cmath>

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

} // namespace overlayd
