// SPDX-License-Identifier: Apache-2.0
// RtspAccess: the GstRTSPAuth of an RTSP sink, and the watch on its refusals.
#include "stream/gst/rtsp_access.h"

#include <set>

namespace overlayd {
namespace {

// The role every accepted credential carries, and the factory grants.
constexpr const char *kViewerRole = "viewer";
// The realm of both challenges, as the HTTP server's Basic one.
constexpr const char *kRtspRealm = "overlayd";

GstRTSPToken *viewerToken()
{
    return gst_rtsp_token_new(GST_RTSP_TOKEN_MEDIA_FACTORY_ROLE, G_TYPE_STRING, kViewerRole, nullptr);
}

// The client's address without its port (its next connection comes from another one).
std::string hostOf(GstRTSPClient *client)
{
    GstRTSPConnection *connection = gst_rtsp_client_get_connection(client);
    return connection ? gst_rtsp_connection_get_ip(connection) : "?";
}

} // namespace

RtspAccess::RtspAccess(const EncodedSinkOptions &options, const EngineLog &log)
    : options_(options), log_(log), failures_(options.key + ": RTSP")
{}

RtspAccess::~RtspAccess()
{
    for (GstRTSPAuth *auth : {auth_, refuser_})
        if (auth != nullptr)
            g_object_unref(auth);
}

Status RtspAccess::apply(GstRTSPServer *server, GstRTSPMediaFactory *factory)
{
    const RtspAccessOptions &access = options_.rtsp.access;
    if (access.users.empty() && access.certPem.empty())
        return Ok{};
    auth_ = gst_rtsp_auth_new();
    refuser_ = gst_rtsp_auth_new();
    if (tls()) {
        GError *error = nullptr;
        GTlsCertificate *certificate =
            g_tls_certificate_new_from_pem((access.certPem + "\n" + access.keyPem).c_str(), -1, &error);
        if (certificate == nullptr) {
            std::string message = options_.key + ": RTSPS certificate: " + (error ? error->message : "?");
            g_clear_error(&error);
            return makeError(ErrorCode::ConfigError, message);
        }
        gst_rtsp_auth_set_tls_certificate(auth_, certificate);
        gst_rtsp_auth_set_tls_certificate(refuser_, certificate);
        g_object_unref(certificate);
    }
    GstRTSPToken *token = viewerToken();
    if (access.users.empty())
        gst_rtsp_auth_set_default_token(auth_, token); // TLS alone: anyone may watch
    // Digest beside basic, so that over plain RTSP a digest client never sends the password itself; but
    // gst-rtsp-server keeps one digest entry per user name, and a viewer and a control token both go by
    // kRtspTokenUser: then basic alone, or a digest client (ffmpeg picks digest when offered) could use one of them.
    std::set<std::string> names;
    for (const RtspUser &user : access.users)
        names.insert(user.name);
    const bool digest = names.size() == access.users.size();
    for (const RtspUser &user : access.users) {
        gchar *basic = gst_rtsp_auth_make_basic(user.name.c_str(), user.password.c_str());
        gst_rtsp_auth_add_basic(auth_, basic, token);
        g_free(basic);
        if (digest)
            gst_rtsp_auth_add_digest(auth_, user.name.c_str(), user.password.c_str(), token);
    }
    for (GstRTSPAuth *auth : {auth_, refuser_}) {
        gst_rtsp_auth_set_supported_methods(
            auth, GstRTSPAuthMethod(GST_RTSP_AUTH_BASIC | (digest ? GST_RTSP_AUTH_DIGEST : 0)));
        gst_rtsp_auth_set_realm(auth, kRtspRealm);
    }
    gst_rtsp_token_unref(token);
    gst_rtsp_media_factory_add_role(factory, kViewerRole, GST_RTSP_PERM_MEDIA_FACTORY_ACCESS, G_TYPE_BOOLEAN, TRUE,
                                    GST_RTSP_PERM_MEDIA_FACTORY_CONSTRUCT, G_TYPE_BOOLEAN, TRUE, nullptr);
    gst_rtsp_server_set_auth(server, auth_);
    return Ok{};
}

void RtspAccess::admit(GstRTSPClient *client)
{
    if (auth_ == nullptr || options_.rtsp.access.users.empty())
        return;
    g_signal_connect(client, "send-message", G_CALLBACK(onSendMessage), this);
    std::lock_guard lock(mutex_);
    if (failures_.blocked(hostOf(client), AuthFailures::Clock::now()))
        gst_rtsp_client_set_auth(client, refuser_);
}

void RtspAccess::onSendMessage(GstRTSPClient *client, GstRTSPContext *context, GstRTSPMessage *message,
                               RtspAccess *self)
{
    GstRTSPStatusCode code = GST_RTSP_STS_OK;
    gchar *authorization = nullptr;
    if (gst_rtsp_message_get_type(message) != GST_RTSP_MESSAGE_RESPONSE ||
        gst_rtsp_message_parse_response(message, &code, nullptr, nullptr) != GST_RTSP_OK ||
        code != GST_RTSP_STS_UNAUTHORIZED || context == nullptr || context->request == nullptr ||
        gst_rtsp_message_get_header(context->request, GST_RTSP_HDR_AUTHORIZATION, &authorization, 0) != GST_RTSP_OK)
        return; // a challenge to a request without a credential is how every client starts
    std::string line;
    {
        std::lock_guard lock(self->mutex_);
        line = self->failures_.failed(hostOf(client), "RTSP basic", AuthFailures::Clock::now());
    }
    if (!line.empty())
        self->log_(kLogWarning, line); // the address, never what was sent
}

} // namespace overlayd
