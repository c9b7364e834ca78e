// Daemon: start-up (signals, timers, config, sinks, the first open of the source) and stopping.
#include "daemon/daemon.h"

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
    if (config.http.enabled)
        sinks.push_back(http_.makeSink());
    builtStream_.reset();
    if (config.stream.enabled()) {
        auto engine = factories_.streamEngine(config.stream, [this](int level, const std::string &message) {
            // syslog priorities, as the engine numbers them
            logger_.log(level <= 3   ? LogLevel::Error
                        : level == 4 ? LogLevel::Warning
                        : level == 5 ? LogLevel::Notice
                        : level == 6 ? LogLevel::Info
                                     : LogLevel::Debug,
                        message);
        });
        if (!engine) {
            status = makeError(engine.error().code, config.stream.sinks.front().key + ": " + engine.error().message);
            return {};
        }
        builtStream_ = std::make_shared<stream::EncodedStream>(config.stream, std::move(*engine));
        sinks.push_back(std::make_unique<SinkWorker>(builtStream_->sink(), SinkOptions{}, logger_));
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

std::vector<inputs::InputHealth> Daemon::inputHealth() const
{
    std::vector<inputs::InputHealth> out = textInputs_.health();
    out.insert(out.end(), pathInputs_.health().begin(), pathInputs_.health().end());
    for (inputs::InputHealth &can : canInputs_.health())
        out.push_back(std::move(can));
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

} // namespace overlayd
