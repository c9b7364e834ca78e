// SPDX-License-Identifier: Apache-2.0
// The module's exported functions: the binary finds them by name (engine_loader.cpp) after dlopen().
#include <gio/gio.h>
#include <gst/gst.h>

#include "stream/gst/encoder_element.h"
#include "stream/gst/gst_stream_engine.h"

using overlayd::EncodedStreamEngine;
using overlayd::EncoderOptions;
using overlayd::EngineLog;
using overlayd::StreamOptions;

namespace {

bool startGstreamer(std::string *error)
{
    GError *initError = nullptr;
    if (gst_init_check(nullptr, nullptr, &initError))
        return true;
    *error = std::string("GStreamer does not start: ") + (initError ? initError->message : "?");
    g_clear_error(&initError);
    return false;
}

} // namespace

extern "C" __attribute__((visibility("default"))) EncodedStreamEngine *
overlayd_stream_create_engine(const StreamOptions *options, const EngineLog *log, std::string *error)
{
    if (!startGstreamer(error))
        return nullptr;
    try { // nothing may throw across the module's boundary
        return new overlayd::GstStreamEngine(*options, *log);
    } catch (const std::exception &e) {
        *error = e.what();
        return nullptr;
    }
}

// The certificate made as RtspAccess makes it, and a TLS backend asked for: without glib-networking GLib has none,
// and the RTSP server could not start.
extern "C" __attribute__((visibility("default"))) bool
overlayd_stream_check_tls(const std::string *certPem, const std::string *keyPem, std::string *error)
{
    if (!startGstreamer(error))
        return false;
    if (!g_tls_backend_supports_tls(g_tls_backend_get_default())) {
        *error = "GLib has no TLS backend for RTSPS (install glib-networking)";
        return false;
    }
    GError *failure = nullptr;
    GTlsCertificate *certificate = g_tls_certificate_new_from_pem((*certPem + "\n" + *keyPem).c_str(), -1, &failure);
    if (certificate == nullptr) {
        *error = std::string("RTSPS certificate: ") + (failure ? failure->message : "?");
        g_clear_error(&failure);
        return false;
    }
    g_object_unref(certificate);
    return true;
}

// The element made as the engine would make it, and dropped: what is not installed is found without a pipeline.
extern "C" __attribute__((visibility("default"))) bool overlayd_stream_check_encoder(const EncoderOptions *options,
                                                                                     std::string *error)
{
    if (!startGstreamer(error))
        return false;
    auto made = overlayd::makeEncoderElement(*options, 0.0);
    if (!made) {
        *error = made.error().message;
        return false;
    }
    gst_object_unref(gst_object_ref_sink(made->element));
    if (made->outputCaps != nullptr)
        gst_caps_unref(made->outputCaps);
    return true;
}
