// SPDX-License-Identifier: Apache-2.0
// A daemon for the fuzz targets that drive the HTTP API: started once from a fixed config written to a folder of its
// own (where the config's relative files live too), with the API it would serve.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unistd.h>

#include "config/daemon_config.h"
#include "control/http_api.h"
#include "daemon/daemon.h"
#include "daemon/stages.h"
#include "daemon/systemd_notify.h"

struct FuzzDaemon {
    std::filesystem::path folder;
    overlayd::Logger logger{[](std::string_view) {}, false};
    overlayd::SystemdNotifier notifier;
    std::unique_ptr<overlayd::Daemon> daemon;
    std::unique_ptr<overlayd::HttpApi> api;

    FuzzDaemon(const std::string &name, std::string_view config)
        : folder(std::filesystem::temp_directory_path() / (name + "-" + std::to_string(getpid())))
    {
        std::filesystem::create_directories(folder);
        const std::string path = (folder / "fuzz.toml").string();
        std::ofstream(path) << config;
        daemon = std::make_unique<overlayd::Daemon>(logger, notifier, overlayd::defaultStageFactories(),
                                                    overlayd::loadConfigFile,
                                                    overlayd::DaemonOptions{path, std::nullopt, 0});
        if (!daemon->start())
            std::abort(); // the fixed config must start: a fuzz run over a daemon that did not is no run
        api = std::make_unique<overlayd::HttpApi>(daemon->scene(), *daemon, [] { return overlayd::HttpCounters{}; });
    }
    ~FuzzDaemon() { std::filesystem::remove_all(folder); }
};
