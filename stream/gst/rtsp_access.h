// SPDX-License-Identifier: Apache-2.0
// RtspAccess: an RTSP sink's credentials and TLS as a GstRTSPAuth: basic users (the [http] users and tokens the
// config resolved), the certificate for RTSPS. A refused credential is logged with the client's address, never the
// secret, once per address per window; beyond kMaxAuthFailures an address's new connections get an auth that knows
// no user, so its guesses are refused without being compared until the window ends.
#pragma once

#include <gst/rtsp-server/rtsp-server.h>

#include <mutex>
#include <string>

#include "base/auth_failures.h"
#include "base/result.h"
#include "stream/encoded_stream_engine.h"

namespace overlayd {

class RtspAccess
{
public:
    RtspAccess(const EncodedSinkOptions &options, const EngineLog &log);
    ~RtspAccess();
    RtspAccess(const RtspAccess &) = delete;
    RtspAccess &operator=(const RtspAccess &) = delete;

    // Puts the auth on the server and the role on the factory; nothing when the sink is open and plain. The error
    // says why the certificate was refused.
    Status apply(GstRTSPServer *server, GstRTSPMediaFactory *factory);
    // A new client: watched for refused credentials, and given the refusing auth while its address is blocked.
    void admit(GstRTSPClient *client);
    bool tls() const { return !options_.rtsp.access.certPem.empty(); }

private:
    static void onSendMessage(GstRTSPClient *client, GstRTSPContext *context, GstRTSPMessage *message,
                              RtspAccess *self);

    EncodedSinkOptions options_;
    EngineLog log_;
    GstRTSPAuth *auth_ = nullptr;    // null: open and plain
    GstRTSPAuth *refuser_ = nullptr; // the same certificate, no user
    std::mutex mutex_;
    AuthFailures failures_;
};

} // namespace overlayd
