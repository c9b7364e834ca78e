// SPDX-License-Identifier: Apache-2.0
// The subcommands of `overlayd`, each returning the process exit status, and the helpers tests check directly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "alignment/point_queries.h"
#include "base/logger.h"
#include "base/number_range.h"
#include "config/daemon_config.h"
#include "daemon/daemon.h"
#include "projection/camera.h"
#include "projection/geometry.h"

namespace overlayd {

// Exit statuses (CLI11 uses its own codes, 100 and up, for command-line errors).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;     // a runtime failure: source, sink, I/O
inline constexpr int kExitConfigError = 2; // the config file, or a number given, does not validate

int checkConfigCommand(const std::string &path);
// `overlayd list-cameras [--json]`: every camera a source could open, with its formats, sizes and frame rates.
int listCamerasCommand(bool json);
// `overlayd list-gpio [--json]`: every GPIO chip with its lines' offsets, names and holders.
int listGpioCommand(bool json);
// `overlayd project [--size WxH] [--points FILE|-] [-- X Y Z ...]`: where world points land, and why not.
int projectCommand(const std::string &configPath, bool json, const std::vector<double> &coordinates,
                   const std::string &pointsPath, const std::string &size, Logger &logger);
// `overlayd unproject [--plane "nx ny nz d"] -- U V ...`: each pixel's world ray and where it meets the plane.
int unprojectCommand(const std::string &configPath, bool json, const std::vector<double> &plane,
                     const std::vector<double> &coordinates, Logger &logger);
// `overlayd solve-pose --points FILE`: the camera pose from world points and their pixels, as config keys.
// --write: also into the config's live drop-in (NAME.live.toml, config/live_drop_in.h) with the whole camera.
// solver: "sqpnp", "iterative" or "ippe" (PnpSolver).
int solvePoseCommand(const std::string &configPath, const std::string &pointsPath, const std::string &solver,
                     bool write, Logger &logger);
// logLevel (from --log-level) overrides the config's daemon.log_level.
int renderCommand(const std::string &configPath, uint64_t frames, const std::string &output,
                  std::optional<LogLevel> logLevel, Logger &logger);
int runCommand(const DaemonOptions &options, Logger &logger);

// Loads a config, logging every problem as "file:line:column: key: message".
Result<DaemonConfig> loadConfigLogged(const std::string &path, Logger &logger);

// A config and its camera built for the configured frame size (a device that negotiates another size scales its
// intrinsics the same way), for the camera-math commands; nothing (every problem logged) when either fails.
struct ConfiguredCamera {
    DaemonConfig config;
    Camera camera;
};
// `size` ("WxH", empty: the config's [source] size) builds it for another stream size without editing the config.
std::optional<ConfiguredCamera> loadCameraLogged(const std::string &path, Logger &logger, const std::string &size = {});

// `render --output PATH`: .y4m -> Y4M, .yuv/.raw -> raw frames, a %d pattern or .png/.jpg -> image snapshots.
Result<SinkOptions> sinkForOutput(const std::string &path);

} // namespace overlayd
