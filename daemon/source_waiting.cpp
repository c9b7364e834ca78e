// SourceSupervisor while the source is down: back-off retries, NO SIGNAL frames, and what systemd is told meanwhile.
#include "daemon/source_supervisor.h"

#include "base/number_text.h"
#include <cstdio>

namespace overlayd {

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
