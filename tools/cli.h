// SPDX-License-Identifier: Apache-2.0
// The command line of `overlayd`: subcommands run (the default), check-config, project, render, list-cameras,
// list-gpio, unproject and solve-pose.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/daemon_config.h"

namespace overlayd {

enum class Command { Run, CheckConfig, Project, Render, ListCameras, ListGpio, Unproject, SolvePose, Exit };

struct CommandLine {
    Command command = Command::Run;
    int exitStatus = 0; // Command::Exit: --help, --version or a usage error (message already printed)
    std::string configPath;
    std::optional<LogLevel> logLevel;
    uint64_t frames = 0;             // run: stop after N frames (0: never); render: how many
    std::string output;              // render
    bool json = false;               // project, list-cameras, list-gpio
    std::vector<double> coordinates; // project: X Y Z ...; unproject: U V ...
    std::vector<double> plane;       // unproject: nx ny nz d (empty: the ground z = 0)
    std::string pointsPath;          // solve-pose; project: X Y Z lines ("-": stdin)
    bool write = false;              // solve-pose: write the pose to the config's live drop-in
    std::string solver = "sqpnp";    // solve-pose: sqpnp | iterative | ippe
    std::string size;                // project: WxH instead of the config's size
};

// Parses argv with CLI11; prints help, version and usage errors itself. Never throws.
CommandLine parseCommandLine(int argc, const char *const *argv);

} // namespace overlayd
