// SPDX-License-Identifier: Apache-2.0
// DaemonConfig: everything one overlayd instance runs from, loaded from a TOML file and validated in one pass.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/logger.h"
#include "base/result.h"
#include "config/camera_spec.h"
#include "drivers/sink_options.h"
#include "drivers/source_options.h"
#include "gpio/gpio_options.h"
#include "http/http_options.h"
#include "inputs/input_options.h"
#include "overlay/shapes/annotation.h"
#include "stream/stream_options.h"

namespace overlayd {

struct DaemonSettings {
    LogLevel logLevel = LogLevel::Info;
    double statsIntervalSec = 10.0; // 0: no periodic stats
};

struct DaemonConfig {
    std::string path;  // the file it came from, for messages
    CameraSpec camera; // builds the stream's Camera once the frame size is known
    OverlayScene scene;
    SourceOptions source; // source.synthetic.camera is filled by the daemon from `camera`
    std::vector<SinkOptions> sinks;
    StreamOptions stream; // [encoder] and the encoded [[sink]]s
    GpioOptions gpio;
    HttpOptions http;
    InputOptions inputs;
    DaemonSettings daemon;
};

// One thing wrong with a config file. line/column are 1-based, 0 when unknown (e.g. a missing key).
struct ConfigProblem {
    std::string file;
    unsigned line = 0, column = 0;
    std::string key;     // dotted path, e.g. "camera.pinhole.fx" or "annotation[2].style.width" (0-based)
    std::string message; // includes "did you mean 'x'?" for unknown keys
    // "file:line:column: key: message"
    std::string format() const;
};

// A config file (and its live drop-in) larger than this is refused before it is read: real ones are a few KiB.
inline constexpr size_t kMaxConfigFileBytes = 1u << 20;

// Parses and validates everything, collecting every problem instead of stopping at the first. Never throws. On
// failure `problems` is non-empty and the result's error (ConfigError) summarizes them. The file must be a regular
// file of at most kMaxConfigFileBytes; a directory, device or FIFO is refused with what it is, without blocking.
Result<DaemonConfig> loadConfigFile(const std::string &path, std::vector<ConfigProblem> &problems);
// The same from text (tests, stdin); `name` stands in for the file name in messages, and relative paths in the
// config resolve against baseDirectory.
Result<DaemonConfig> loadConfigText(std::string_view text, const std::string &name, const std::string &baseDirectory,
                                    std::vector<ConfigProblem> &problems);

} // namespace overlayd
