// SPDX-License-Identifier: Apache-2.0
// The GStreamer engine is a module (overlayd-stream.so) that the daemon loads only when an encoded sink is
// configured: a camera-only run, `--version` and `check-config` never map GStreamer. The module stays loaded
// once loaded (GLib's type system cannot be unloaded).
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd {

// A new engine from the module: found next to the running binary (the build tree) or in the library folder it
// was installed to. An error names every place it looked, or what dlopen said.
Result<std::unique_ptr<EncodedStreamEngine>> loadStreamEngine(const StreamOptions &options, const EngineLog &log);

// Whether the encoder the options ask for is on this machine (its GStreamer element installed; for v4l2 an M2M
// H.264 encoder, at `device` if one is named), asked of the module: the config loader refuses it at its key. Ok
// when the module itself is not found, unless requireStreamModule() was called, or the build has no encoded outputs.
Status checkEncoder(const EncoderOptions &options);

// Whether GLib can serve RTSPS with this certificate and key (PEM), asked of the module: the config loader refuses a
// sink that run could not start at its `tls` key. Ok when the module is not found, as checkEncoder().
Status checkRtspsCertificate(const std::string &certPem, const std::string &keyPem);

// From now on checkEncoder() and checkRtspsCertificate() refuse a module that cannot be loaded, with loadStreamEngine's
// message: the binary's `check-config` and `run` call it, so that check-config refuses what run would not start. A unit
// test of the config loader leaves it off: its binary has no module beside it, and what it tests is the parsing.
void requireStreamModule();

} // namespace overlayd
