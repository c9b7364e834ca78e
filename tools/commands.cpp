// SPDX-License-Identifier: Apache-2.0
// `overlayd check-config` and `overlayd run`, and config loading with every problem reported.
#include "tools/commands.h"

#include <cstdio>
#include <filesystem>

#include "config/live_drop_in.h"
#include "daemon/systemd_notify.h"
#include "media/frame.h"
#include "tools/startup_guard.h"

namespace overlayd {

namespace {

// A command that reads NAME.live.toml says so: its camera is not the one the user reads in NAME.toml. "" when there
// is none.
std::string liveDropInNote(const std::string &path)
{
    const std::string dropIn = liveDropInPath(path);
    std::error_code absent;
    if (!std::filesystem::exists(dropIn, absent))
        return {};
    return "using the live pose from " + dropIn + " (written by POST /api/save or solve-pose --write; delete it to " +
           "use the camera of " + path + ")";
}

} // namespace

Result<DaemonConfig> loadConfigLogged(const std::string &path, Logger &logger)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(path, problems);
    if (!config) {
        for (const ConfigProblem &problem : problems)
            logger.error(problem.format());
        if (problems.empty())
            logger.error(cat(path, ": ", config.error().message));
    } else if (const std::string note = liveDropInNote(path); !note.empty()) {
        logger.notice(note);
    }
    return config;
}

std::optional<ConfiguredCamera> loadCameraLogged(const std::string &path, Logger &logger, const std::string &size)
{
    auto config = loadConfigLogged(path, logger);
    if (!config)
        return std::nullopt;
    unsigned width = config->source.width, height = config->source.height;
    if (!size.empty()) {
        unsigned w = 0, h = 0;
        char end = 0;
        if (std::sscanf(size.c_str(), "%ux%u%c", &w, &h, &end) != 2 || w == 0 || h == 0 || w > kMaxFrameDimension ||
            h > kMaxFrameDimension) {
            logger.error(cat("--size ", size, ": expected WIDTHxHEIGHT, each 1..", kMaxFrameDimension));
            return std::nullopt;
        }
        width = w;
        height = h;
    }
    auto camera = config->camera.build(width, height);
    if (!camera) {
        logger.error(cat(path, ": camera: ", camera.error().message));
        return std::nullopt;
    }
    if (const std::string scaling = config->camera.calibrationScaling(camera->viewport()); !scaling.empty())
        logger.info(scaling);
    return ConfiguredCamera{std::move(*config), std::move(*camera)};
}

int checkConfigCommand(const std::string &path)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(path, problems);
    if (const std::string note = liveDropInNote(path); !note.empty())
        std::fprintf(stderr, "%s\n", note.c_str());
    for (const ConfigProblem &problem : problems)
        std::printf("%s\n", problem.format().c_str());
    if (!config) {
        if (problems.empty())
            std::printf("%s: %s\n", path.c_str(), config.error().message.c_str());
        std::printf("%s: %zu problem(s)\n", path.c_str(), problems.size());
        return kExitConfigError;
    }
    std::printf("%s: OK\n", path.c_str());
    return kExitOk;
}

int runCommand(const DaemonOptions &options, Logger &logger)
{
    // First of all: from here a stop signal ends start-up at once, whatever start-up is blocked in; once the loop
    // runs, its own signalfd takes over (the signals stay blocked throughout: daemon/early_signals.cpp).
    auto guard = StartupGuard::start(logger, kExitOk);
    if (!guard) {
        logger.error(guard.error().message);
        return kExitFailure;
    }
    const std::unique_ptr<SystemdNotifier> notifier = SystemdNotifier::fromEnvironment();
    Daemon daemon(logger, *notifier, defaultStageFactories(), loadConfigFile, options);
    const Status started = daemon.start();
    guard->reset(); // a stop signal from now on is the loop's, or waits for the failed start-up's exit status
    if (!started) { // start() has logged why
        notifier->stopping();
        return started.error().code == ErrorCode::ConfigError ? kExitConfigError : kExitFailure;
    }
    return daemon.run();
}

} // namespace overlayd
