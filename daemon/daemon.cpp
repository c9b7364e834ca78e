// Daemon: start-up, opening and closing the source, and the frame path while streaming.
#include "daemon/daemon.h"

#include <cmath>

namespace overlayd {

std::chrono::nanoseconds Daemon::framePeriod(double fps)
{
    return std::chrono::nanoseconds(int64_t(std::llround(1e9 / fps)));
}

Daemon::Daemon(Logger &logger, SystemdNotifier &notifier, StageFactories factories, ConfigLoader loader,
               DaemonOptions options)
    : logger_(logger), notifier_(notifier), factories_(std::move(factories)), loader_(std::move(loader)),
      options_(std::move(options)), pipeline_(logger), scene_(factories_.renderer)
{}

Daemon::~Daemon()
{
    closeSource();
}

Status Daemon::start()
{
    Status status = setUp();
    // The config loader's problems are logged one per line where they are found; any other refusal is logged here,
    // once, so that no failure leaves the process with exit status 2 and nothing said.
    if (!status && !configProblemsLogged_)
        logger_.error(status.error().message);
    return status;
}

Status Daemon::setUp()
{
    auto signals = SignalReader::create();
    if (!signals)
        return signals.error();
    signals_.emplace(std::move(*signals));
    for (auto *timer : {&pacing_, &retry_, &noSignalTimer_, &stats_, &watchdog_}) {
        auto created = Timer::create();
        if (!created)
            return created.error();
        timer->emplace(std::move(*created));
    }
    std::vector<ConfigProblem> problems;
    auto loaded = loader_(options_.configPath, problems);
    if (!loaded) {
        for (const ConfigProblem &problem : problems)
            logger_.error(problem.format());
        configProblemsLogged_ = !problems.empty();
        return loaded.error();
    }
    config_ = std::move(*loaded);
    scene_.load(config_.scene, config_.camera);
    applyLogLevel();
    Status sinksBuilt = Ok{};
    pipeline_.setSinks(buildSinks(config_, sinksBuilt));
    if (!sinksBuilt)
        return sinksBuilt;
    if (auto opened = openSource(); !opened) {
        if (!isRetryable(opened.error()))
            return opened;
        enterWaiting(opened.error());
    }
    if (pipeline_.format().format == nullptr)
        return makeError(ErrorCode::InvalidArgument, "no stream format");
    armStats();
    if (auto interval = notifier_.watchdogInterval())
        (void)watchdog_->arm(*interval, *interval);
    return Ok{};
}

std::vector<std::unique_ptr<SinkWorker>> Daemon::buildSinks(const DaemonConfig &config, Status &status)
{
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    std::vector<SinkOptions> all = config.sinks;
    std::vector<std::string> notices;
    if (auto limited = limitZeroCopy(all, notices); !limited) {
        status = limited;
        return {};
    }
    for (const std::string &notice : notices)
        logger_.notice(notice);
    for (const SinkOptions &options : all) {
        auto sink = factories_.sink(options);
        if (!sink) {
            status = makeError(sink.error().code, "sink '" + options.path + "': " + sink.error().message);
            return {};
        }
        sinks.push_back(std::make_unique<SinkWorker>(std::move(*sink), options, logger_));
    }
    return sinks;
}

Status Daemon::openSource()
{
    auto source = factories_.source(config_);
    if (!source)
        return source.error();
    auto format = (*source)->start();
    if (!format)
        return format.error();
    auto renderer = scene_.build(*format);
    if (!renderer) {
        (*source)->stop();
        return renderer.error();
    }
    const StreamFormat &current = pipeline_.format();
    const bool formatChanged = current.format != format->format || current.width != format->width ||
                               current.height != format->height || current.stride != format->stride ||
                               !(current.colorimetry == format->colorimetry) || current.fps != format->fps ||
                               current.dmabufBuffers != format->dmabufBuffers;
    if (formatChanged) {
        if (auto opened = pipeline_.openSinks(*format); !opened && state_ == State::Idle) {
            (*source)->stop();
            return opened;
        }
    }
    pipeline_.setRenderer(std::move(*renderer));
    scene_.attach(pipeline_.renderer(), *format);
    source_ = std::move(*source);
    logger_.notice(cat("streaming from ", source_->describe(), ": ", format->describe()));
    if (source_->eventFd() >= 0 && loop_) {
        watchedSourceFd_ = source_->eventFd();
        (void)loop_->add(watchedSourceFd_, [this] { onFrameReady(); });
    } else if (source_->eventFd() < 0) {
        (void)pacing_->arm(framePeriod(pacingFps()), framePeriod(pacingFps()));
    }
    noSignalTimer_->disarm();
    retry_->disarm();
    noSignal_.reset();
    waitReason_.clear();
    backoff_.reset();
    state_ = State::Streaming;
    updateStatus();
    return Ok{};
}

void Daemon::closeSource()
{
    if (loop_ && watchedSourceFd_ >= 0)
        loop_->remove(watchedSourceFd_);
    watchedSourceFd_ = -1;
    if (pacing_)
        pacing_->disarm();
    if (source_)
        source_->stop();
    source_.reset();
}

void Daemon::onFrameReady()
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
        ++framesSincePet_;
        if (!readySent_) {
            readySent_ = true;
            notifier_.ready();
            updateStatus();
        }
        if (options_.maxFrames && pipeline_.framesIn() >= options_.maxFrames) {
            logger_.info(cat("frame limit reached (", options_.maxFrames, " frames)"));
            requestStop(0);
        }
    }
}

void Daemon::handleSourceError(const Error &error)
{
    if (error.code == ErrorCode::TryAgain)
        return;
    if (error.code == ErrorCode::EndOfStream) {
        logger_.notice(cat("source ended after ", pipeline_.framesIn(), " frames"));
        requestStop(0);
    } else if (isRetryable(error)) {
        enterWaiting(error);
    } else {
        logger_.error(cat("source: ", error.message));
        requestStop(1);
    }
}

void Daemon::requestStop(int exitStatus)
{
    exitStatus_ = std::max(exitStatus_, exitStatus);
    state_ = State::Finished;
    if (loop_)
        loop_->stop();
}

} // namespace overlayd
