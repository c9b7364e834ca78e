// SPDX-License-Identifier: Apache-2.0
// The module's one exported function: the binary finds it by name (engine_loader.cpp) after dlopen().
#include <gst/gst.h>

#include "stream/gst/gst_stream_engine.h"

using overlayd::stream::EncodedStreamEngine;
using overlayd::stream::EngineLog;
using overlayd::stream::StreamOptions;

extern "C" __attribute__((visibility("default"))) EncodedStreamEngine *
overlayd_stream_create_engine(const StreamOptions *options, const EngineLog *log, std::string *error)
{
    GError *initError = nullptr;
    if (!gst_init_check(nullptr, nullptr, &initError)) {
        *error = std::string("GStreamer does not start: ") + (initError ? initError->message : "?");
        g_clear_error(&initError);
        return nullptr;
    }
    try { // nothing may throw across the module's boundary
        return new overlayd::stream::gst::GstStreamEngine(*options, *log);
    } catch (const std::exception &e) {
        *error = e.what();
        return nullptr;
    }
}
