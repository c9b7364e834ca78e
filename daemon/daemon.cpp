// SPDX-License-Identifier: Apache-2.0
// Daemon: start-up (signals, timers, config, sinks, the first open of the source) and stopping; then the event
// loop's wiring, periodic stats and the watchdog; then SIGHUP reloads.
#include "daemon/daemon.h"

#include <csignal>
#include <cstdio>
#include <cstring>

#include "daemon/rollback.h"

namespace overlayd {

Daemon::Daemon(Logger &logger, SystemdNotifier &notifier, StageFactories factories, ConfigLoader loader,
               DaemonOptions options)
    : logger_(logger), factories_(std::move(factories)), loader_(std::move(loader)), options_(std::move(options)),
      pipeline_(logger), scene_(factories_.renderer), health_(logger, notifier), gpio_(logger, scene_),
      textInputs_(logger, scene_), pathInputs_(logger, scene_), canInputs_(logger, scene_), http_(logger, scene_, *this)
{
    pipeline_.setRawTap([this](const FrameView &frame, const FrameMetadata &metadata) {
        if (http_.running())
            http_.onRawFrame(frame, metadata);
    });
    if (factories_.gpio)
        gpio_.setProvider(factories_.gpio());
}

Daemon::~Daemon()
{
    source_.reset();
    // The sink threads stop before the members they write to (the HTTP side's JPEG feed) are destroyed.
    pipeline_.closeSinks();
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

Status Daemon::createTimers()
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
    source_ = std::make_unique<SourceSupervisor>(
        logger_, config_, factories_.source, pipeline_, scene_, health_,
        SourceSupervisor::Timers{*pacing_, *retry_, *noSignalTimer_}, [this] { onFrameDelivered(); },
        [this](int exitStatus) { requestStop(exitStatus); });
    return Ok{};
}

Status Daemon::setUp()
{
    if (auto created = createTimers(); !created)
        return created;
    std::vector<ConfigProblem> problems;
    auto loaded = loadConfig(problems);
    if (!loaded) {
        configProblemsLogged_ = !problems.empty();
        return loaded.error();
    }
    config_ = std::move(*loaded);
    scene_.load(config_.scene, config_.camera);
    applyLogLevel();
    // Input states are read before the first frame: a car started in reverse shows the guide lines at once.
    if (!config_.gpio.empty()) {
        if (auto lines = gpio_.configure(config_.gpio); !lines)
            return lines;
        gpio_.applyLayers();
    }
    if (auto watched = textInputs_.configure(config_.inputs.text); !watched)
        return watched;
    if (auto watched = pathInputs_.configure(config_.inputs.paths); !watched)
        return watched;
    pathInputs_.showAll();
    canInputs_.configure(config_.inputs.can);
    if (auto served = http_.configure(config_.http); !served)
        return served;
    Status sinksBuilt = Ok{};
    pipeline_.setSinks(buildSinks(config_, sinksBuilt));
    stream_ = builtStream_;
    if (!sinksBuilt)
        return sinksBuilt;
    if (auto opened = source_->open(); !opened) {
        if (!source_->isRetryable(opened.error()))
            return opened;
        source_->enterWaiting(opened.error());
    }
    if (pipeline_.format().format == nullptr)
        return makeError(ErrorCode::InvalidArgument, "no stream format");
    armStats();
    if (auto interval = health_.notifier().watchdogInterval())
        (void)watchdog_->arm(*interval, *interval);
    return Ok{};
}

Result<DaemonConfig> Daemon::loadConfig(std::vector<ConfigProblem> &problems)
{
    auto loaded = loader_(options_.configPath, problems);
    for (const ConfigProblem &problem : problems)
        logger_.error(problem.format());
    return loaded;
}

namespace {

// The encoded outputs' sink: its name is its /state and /metrics identity, as the HTTP JPEG feed is "http". Its RTSP
// ports and record directories are one place, its path, that a reload's new encoder takes over: it opens only once
// the running one has closed (Pipeline::replaceSinks). No file sink's path begins with '['.
constexpr const char *kEncoderSinkName = "encoder";
constexpr const char *kEncoderSinkPath = "[encoder]";

bool isEncoderSink(const SinkWorker &sink)
{
    return sink.options().name == kEncoderSinkName && sink.options().path == kEncoderSinkPath;
}

} // namespace

std::vector<std::unique_ptr<SinkWorker>> Daemon::buildSinks(const DaemonConfig &config, Status &status, bool keepStream)
{
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    std::vector<SinkOptions> all = config.sinks;
    std::vector<std::string> notices;
    StreamOptions streamOptions = config.stream;
    if (auto limited = limitZeroCopy(all, notices); !limited) {
        status = limited;
        return {};
    }
    if (auto limited = limitEncoderZeroCopy(all, streamOptions.encoder, notices); !limited) {
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
    if (config.http.enabled)
        sinks.push_back(std::make_unique<SinkWorker>(http_.makeSink(), HttpFront::sinkOptions(), logger_));
    builtStream_ = keepStream ? stream_ : nullptr;
    if (config.stream.enabled() && !keepStream) {
        const EngineLog log = [this](int level, const std::string &message) {
            // syslog priorities, as the engine numbers them
            logger_.log(level <= 3   ? LogLevel::Error
                        : level == 4 ? LogLevel::Warning
                        : level == 5 ? LogLevel::Notice
                        : level == 6 ? LogLevel::Info
                                     : LogLevel::Debug,
                        message);
        };
        auto engine = factories_.streamEngine(streamOptions, log);
        if (!engine) {
            const std::string key = config.stream.sinks.empty() ? "webrtc" : config.stream.sinks.front().key;
            status = makeError(engine.error().code, key + ": " + engine.error().message);
            return {};
        }
        builtStream_ = std::make_shared<EncodedStream>(streamOptions, std::move(*engine));
        builtStream_->setLog(log);
        SinkOptions encoder;
        encoder.name = kEncoderSinkName;
        encoder.path = kEncoderSinkPath;
        sinks.push_back(std::make_unique<SinkWorker>(builtStream_->sink(), encoder, logger_));
    }
    return sinks;
}

uint64_t Daemon::sinkFailures() const
{
    uint64_t failures = 0;
    for (const auto &sink : pipeline_.sinks())
        failures += sink->counters().failed;
    return failures;
}

std::vector<const StatusReporter *> Daemon::reporters() const
{
    std::vector<const StatusReporter *> out;
    for (const auto &sink : pipeline_.sinks())
        out.push_back(sink.get());
    out.insert(out.end(), {&gpio_, &textInputs_, &pathInputs_, &canInputs_, &streamReport_});
    return out;
}

void Daemon::onFrameDelivered()
{
    if (!gpio_.empty())
        gpio_.onFrameDelivered(gpio_.wantsSinkFailures() ? sinkFailures() : 0);
    if (options_.maxFrames && pipeline_.framesIn() >= options_.maxFrames) {
        logger_.info(cat("frame limit reached (", options_.maxFrames, " frames)"));
        requestStop(0);
    }
}

void Daemon::requestStop(int exitStatus)
{
    exitStatus_ = std::max(exitStatus_, exitStatus);
    if (source_)
        source_->finish();
    if (loop_)
        loop_->stop();
}

// The event loop's wiring, periodic stats, the watchdog and shutdown.

int Daemon::run()
{
    auto loop = EventLoop::create();
    if (!loop || !signals_) {
        logger_.error(cat("event loop: ", !loop ? loop.error().message : "start() did not succeed"));
        return 1;
    }
    loop_ = &*loop;
    loop->setFailureLog(
        [this](const std::string &what) { logger_.error("event loop: a handler failed and was skipped: " + what); });
    (void)loop->add(signals_->fd(), [this] {
        while (const int signal = signals_->read()) {
            if (signal == SIGHUP) {
                reload();
                continue;
            }
            logger_.notice(cat("stopping on ", sigabbrev_np(signal) ? sigabbrev_np(signal) : "signal"));
            requestStop(0);
        }
    });
    (void)loop->add(pacing_->fd(), [this] {
        if (pacing_->consume())
            onFrameReady();
    });
    (void)loop->add(retry_->fd(), [this] { onRetry(); });
    (void)loop->add(noSignalTimer_->fd(), [this] { onNoSignalTick(); });
    (void)loop->add(stats_->fd(), [this] { onStats(); });
    (void)loop->add(watchdog_->fd(), [this] { onWatchdog(); });
    source_->attachLoop(loop_);
    gpio_.attachLoop(loop_);
    http_.attachLoop(loop_);
    textInputs_.attachLoop(loop_);
    pathInputs_.attachLoop(loop_);
    canInputs_.attachLoop(loop_);
    while (state() != State::Finished) {
        gpio_.onState(state()); // outputs follow the state the last turn left
        if (auto status = loop->runOnce(); !status) {
            logger_.error(status.error().message);
            requestStop(1);
        }
    }
    shutdown();
    canInputs_.attachLoop(nullptr);
    pathInputs_.attachLoop(nullptr);
    textInputs_.attachLoop(nullptr);
    http_.attachLoop(nullptr);
    gpio_.attachLoop(nullptr);
    source_->attachLoop(nullptr);
    loop_ = nullptr;
    return exitStatus_;
}

void Daemon::shutdown()
{
    health_.notifier().stopping();
    gpio_.shutdown(); // outputs back to their inactive level
    source_->close();
    pipeline_.closeSinks();
    const PipelineStats stats = pipeline_.takeStats();
    logger_.info(cat("stopped after ", pipeline_.framesIn(), " frames; last period: ", stats.describe()));
    logger_.flush();
}

void Daemon::onStats()
{
    stats_->consume();
    health_.onStats(pipeline_, state() == State::Streaming);
    if (!gpio_.empty())
        logger_.info(cat("gpio: ", gpio_.describe()));
    if (canInputs_.size() > 0)
        logger_.info(cat("input.can: ", canInputs_.describe(CanInputs::Clock::now())));
}

void Daemon::onWatchdog()
{
    watchdog_->consume();
    health_.onWatchdog(state() == State::Streaming, state() == State::Waiting, pipeline_.format(), source_->describe());
}

void Daemon::armStats()
{
    const double interval = config_.daemon.statsIntervalSec;
    if (interval > 0) {
        const auto period = std::chrono::nanoseconds(int64_t(interval * 1e9));
        (void)stats_->arm(period, period);
    } else {
        stats_->disarm();
    }
}

void Daemon::applyLogLevel()
{
    logger_.setLevel(options_.logLevel.value_or(config_.daemon.logLevel));
}

// SIGHUP reloads, as a transaction. The whole new config is built and opened (source, overlay, GPIO lines,
// file inputs, HTTP server, sinks) while the old one still runs; only when every part is ready is it switched,
// between two frames. A part that fails refuses the reload: what was already switched in place is put back, the
// log and STATUS= say why, and the old config streams on as if the reload had not been asked for.

namespace {

// "overlayd.toml:16:1: sink[0].knd: unknown key (and 2 more problems)": the first problem for STATUS=, where the
// log has them all.
std::string summary(const std::vector<ConfigProblem> &problems, const Error &error)
{
    if (problems.empty())
        return error.message;
    if (problems.size() == 1)
        return problems.front().format();
    return cat(problems.front().format(), " (and ", problems.size() - 1, " more problems)");
}

// A failure that the file's contents caused (a source, an overlay or a sink it asks for) names the file.
Error inFile(const DaemonConfig &config, const char *part, const Error &error)
{
    return makeError(error.code, cat(config.path, ": ", part, ": ", error.message));
}

} // namespace

bool Daemon::reload()
{
    SystemdNotifier &notifier = health_.notifier();
    notifier.reloading();
    logger_.notice(cat("reloading ", options_.configPath));
    std::vector<ConfigProblem> problems;
    auto loaded = loadConfig(problems);
    auto switched = loaded ? switchConfig(std::move(*loaded)) : Result<ReopenedParts>(loaded.error());
    if (!switched) {
        const std::string why = loaded ? switched.error().message : summary(problems, loaded.error());
        logger_.error(cat("reload refused, kept the previous config: ", why));
        health_.reloadRefused(why);
        notifier.ready();
        return false;
    }
    logger_.notice(cat("reloaded ", options_.configPath, switched->source ? " (source re-opened)" : "",
                       switched->sinks ? " (sinks re-opened)" : ""));
    health_.reloadAccepted();
    if (state() == State::Streaming)
        health_.streaming(pipeline_.format());
    notifier.ready();
    return true;
}

Result<Daemon::ReopenedParts> Daemon::switchConfig(DaemonConfig next)
{
    // Whole option structs are compared: a field added to them later re-opens what it belongs to.
    const bool sourceChanged = config_.source != next.source || sceneCameraChanged(config_, next) ||
                               wantsZeroCopy(config_) != wantsZeroCopy(next);
    const bool sinksChanged =
        config_.sinks != next.sinks || config_.http.enabled != next.http.enabled || config_.stream != next.stream;
    // The same [encoder] and encoded sinks: the running engine goes on, and its RTSP clients with it.
    const bool streamKept = stream_ && config_.stream == next.stream;
    // The candidate scene carries the live layer choices and slot texts; the live one is not touched until the switch.
    SceneControl scene = scene_.withScene(next.scene, next.camera);
    std::optional<SourceSupervisor::Staged> stream;
    std::unique_ptr<OverlayRenderer> renderer;
    Rollback rollback; // after what its steps refer to, so that it runs before they go

    // The new source and its overlay, or the new overlay for the running stream.
    StreamFormat format = pipeline_.format();
    if (sourceChanged) {
        auto staged = source_->stage(next, scene);
        if (!staged)
            return inFile(next, "source", staged.error());
        stream = std::move(*staged);
        format = stream->stream.format;
        rollback.add([this, &stream] { source_->discard(std::move(*stream)); });
    } else if (state() == State::Streaming) {
        auto built = scene.build(format);
        if (!built)
            return inFile(next, "overlay", built.error());
        renderer = std::move(*built);
    }
    // GPIO lines, file watches and the HTTP server change in place (a line already held, a folder that cannot be
    // watched, a port already taken refuse the reload), and go back if a later step refuses it.
    if (config_.gpio != next.gpio) {
        if (auto lines = gpio_.configure(next.gpio); !lines)
            return lines.error();
        rollback.add([this] { (void)gpio_.configure(config_.gpio); });
    }
    if (config_.inputs != next.inputs) {
        if (auto watched = textInputs_.configure(next.inputs.text); !watched)
            return watched.error();
        rollback.add([this] { (void)textInputs_.configure(config_.inputs.text); });
        if (auto watched = pathInputs_.configure(next.inputs.paths); !watched)
            return watched.error();
        rollback.add([this] { (void)pathInputs_.configure(config_.inputs.paths); });
    }
    if (config_.http != next.http) {
        if (auto served = http_.configure(next.http); !served)
            return served.error();
        rollback.add([this] { (void)http_.configure(config_.http); });
    }
    // The sinks last: a sink that takes over a running one's file or device opens only after the running ones have
    // closed, and the pipeline re-opens them itself if it fails.
    if (sinksChanged) {
        Status built = Ok{};
        auto sinks = buildSinks(next, built, streamKept);
        if (!built)
            return inFile(next, "sink", built.error());
        const Pipeline::KeepSink keep = [streamKept](const SinkWorker &sink) {
            return streamKept && isEncoderSink(sink);
        };
        if (auto replaced = pipeline_.replaceSinks(std::move(sinks), format, keep); !replaced)
            return inFile(next, "sink", replaced.error());
        stream_ = builtStream_;
    } else if (format.format && format != pipeline_.format()) {
        if (auto reopened = pipeline_.reopenSinks(format); !reopened)
            return inFile(next, "sink", reopened.error());
    }
    rollback.commit();
    commitConfig(std::move(next), std::move(scene), std::move(stream), std::move(renderer));
    return ReopenedParts{sourceChanged, sinksChanged};
}

void Daemon::commitConfig(DaemonConfig next, SceneControl scene, std::optional<SourceSupervisor::Staged> stream,
                          std::unique_ptr<OverlayRenderer> renderer)
{
    const bool gpioChanged = config_.gpio != next.gpio;
    const bool inputsChanged = config_.inputs != next.inputs;
    config_ = std::move(next);
    scene_ = std::move(scene);
    if (stream) {
        source_->adopt(std::move(*stream));
    } else if (state() == State::Streaming) {
        pipeline_.setRenderer(std::move(renderer));
        scene_.attach(pipeline_.renderer(), pipeline_.format());
    }
    if (gpioChanged)
        gpio_.applyLayers(); // the new rules, on the new scene's layers
    textInputs_.showAll();   // the files' lines in the new scene's slots
    pathInputs_.showAll();   // and their points in its polylines and markers
    if (inputsChanged)       // CAN inputs cannot refuse a reload: an interface that is not there is retried
        canInputs_.configure(config_.inputs.can);
    else
        canInputs_.showAll(); // the signals' values on the new scene's guide lines and slots
    applyLogLevel();
    armStats();
}

} // namespace overlayd
