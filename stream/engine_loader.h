// SPDX-License-Identifier: Apache-2.0
// The GStreamer engine is a module (overlayd-stream.so) that the daemon loads only when an encoded sink is
// configured: a camera-only run, `--version` and `check-config` never map GStreamer. The module stays loaded
// once loaded (GLib's type system cannot be unloaded).
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd::stream {

// A new engine from the module: found next to the running binary (the build tree) or in the library folder it
// was installed to. An error names every place it looked, or what dlopen said.
Result<std::unique_ptr<EncodedStreamEngine>> loadStreamEngine(const StreamOptions &options, const EngineLog &log);

} // namespace overlayd::stream
