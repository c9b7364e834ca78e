// Daemon: SIGHUP reloads, as a transaction. The whole new config is built and opened (source, overlay, GPIO lines,
// file inputs, HTTP server, sinks) while the old one still runs; only when every part is ready is it switched,
// between two frames. A part that fails refuses the reload: what was already switched in place is put back, the
// log and STATUS= say why, and the old config streams on as if the reload had not been asked for.
#include "daemon/daemon.h"

#include "daemon/rollback.h"

namespace overlayd {

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
        auto sinks = buildSinks(next, built);
        if (!built)
            return inFile(next, "sink", built.error());
        if (auto replaced = pipeline_.replaceSinks(std::move(sinks), format); !replaced)
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
