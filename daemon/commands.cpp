// `overlayd check-config` and `overlayd run`, and config loading with every problem reported.
#include "daemon/commands.h"

#include <cstdio>

#include "daemon/systemd_notify.h"

namespace overlayd {

Result<DaemonConfig> loadConfigLogged(const std::string &path, Logger &logger)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(path, problems);
    if (!config) {
        for (const ConfigProblem &problem : problems)
            logger.error(problem.format());
        if (problems.empty())
            logger.error(cat(path, ": ", config.error().message));
    }
    return config;
}

std::optional<ConfiguredCamera> loadCameraLogged(const std::string &path, Logger &logger)
{
    auto config = loadConfigLogged(path, logger);
    if (!config)
        return std::nullopt;
    auto camera = config->camera.build(config->source.width, config->source.height);
    if (!camera) {
        logger.error(cat(path, ": camera: ", camera.error().message));
        return std::nullopt;
    }
    return ConfiguredCamera{std::move(*config), std::move(*camera)};
}

int checkConfigCommand(const std::string &path)
{
    std::vector<ConfigProblem> problems;
    auto config = loadConfigFile(path, problems);
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
    const std::unique_ptr<SystemdNotifier> notifier = SystemdNotifier::fromEnvironment();
    Daemon daemon(logger, *notifier, defaultStageFactories(), loadConfigFile, options);
    if (auto started = daemon.start(); !started) { // start() has logged why
        notifier->stopping();
        return started.error().code == ErrorCode::ConfigError ? kExitConfigError : kExitFailure;
    }
    return daemon.run();
}

} // namespace overlayd
