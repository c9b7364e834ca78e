// Daemon: the source's error handling: back-off retries and NO SIGNAL frames while it is down, the end of a stream.
#include "daemon/daemon.h"

#include <cstdio>

namespace overlayd {

namespace {

std::string seconds(std::chrono::milliseconds delay)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%g s", double(delay.count()) / 1000.0);
    return text;
}

} // namespace

bool Daemon::isRetryable(const Error &error) const
{
    // A camera that is unplugged, not yet plugged or misbehaving comes back by itself; a file that is missing or
    // malformed does not, except that a reload may fix it.
    if (error.code == ErrorCode::DeviceLost || error.code == ErrorCode::TryAgain)
        return true;
    return config_.source.kind == SourceKind::V4l2 &&
           (error.code == ErrorCode::NotFound || error.code == ErrorCode::Io);
}

void Daemon::enterWaiting(const Error &error)
{
    closeSource();
    state_ = State::Waiting;
    if (error.message != waitReason_)
        logger_.warning(cat("source lost: ", error.message));
    waitReason_ = error.message;
    const StreamFormat format = pipeline_.format().format ? pipeline_.format() : configuredFormat();
    if (!pipeline_.format().format)
        (void)pipeline_.openSinks(format);
    if (!noSignal_ || noSignal_->reason() != waitReason_) {
        auto frame = NoSignalFrame::create(format, waitReason_);
        if (frame)
            noSignal_.emplace(std::move(*frame));
        else
            logger_.error(cat("NO SIGNAL frame: ", frame.error().message));
    }
    (void)noSignalTimer_->arm(framePeriod(pacingFps()), framePeriod(pacingFps()));
    scheduleRetry();
}

void Daemon::scheduleRetry()
{
    const auto delay = backoff_.next();
    (void)retry_->arm(delay);
    logger_.debug(cat("retrying the source in ", seconds(delay)));
    // Before the first frame systemd is still waiting for READY=1: a camera that is late at boot must not fail the
    // unit's start-up timeout, so ask for time until the retry plus a margin.
    if (!readySent_)
        notifier_.extendTimeout(std::chrono::duration_cast<std::chrono::microseconds>(delay) +
                                std::chrono::seconds(10));
    updateStatus();
    if (state_ == State::Waiting)
        notifier_.status(
            cat("waiting for ",
                config_.source.kind == SourceKind::V4l2 ? config_.source.v4l2.device : std::string("the source"), ": ",
                waitReason_, ", retry in ", seconds(delay)));
}

void Daemon::onRetry()
{
    retry_->consume();
    if (state_ != State::Waiting)
        return;
    auto opened = openSource();
    if (opened) {
        logger_.notice("source is back");
        return;
    }
    if (opened.error().message != waitReason_) {
        logger_.warning(cat("source still down: ", opened.error().message));
        waitReason_ = opened.error().message;
        noSignal_.reset();
        if (auto frame = NoSignalFrame::create(pipeline_.format(), waitReason_))
            noSignal_.emplace(std::move(*frame));
    }
    scheduleRetry();
}

void Daemon::onNoSignalTick()
{
    noSignalTimer_->consume();
    if (state_ != State::Waiting || !noSignal_)
        return;
    FrameMetadata metadata;
    metadata.sequence = noSignalSequence_++;
    metadata.timestamp = std::chrono::steady_clock::now().time_since_epoch();
    metadata.wallClock = std::chrono::system_clock::now();
    metadata.colorimetry = noSignal_->format().colorimetry;
    pipeline_.pushToSinks(noSignal_->view(), metadata);
}

StreamFormat Daemon::configuredFormat() const
{
    StreamFormat format;
    format.format = pixelFormatFromName(config_.source.pixelFormat);
    if (!format.format)
        format.format = pixelFormatFromName("YUYV");
    format.width = config_.source.width;
    format.height = config_.source.height;
    format.fps = config_.source.fps;
    format.colorimetry = config_.source.colorimetry.value_or(Colorimetry{});
    return format;
}

double Daemon::pacingFps() const
{
    // fps 0 means "as fast as frames come", which only `render` does; a running daemon paces at a sane default.
    if (pipeline_.format().fps > 0)
        return pipeline_.format().fps;
    return config_.source.fps > 0 ? config_.source.fps : 30.0;
}

} // namespace overlayd
