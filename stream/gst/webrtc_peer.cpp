// SPDX-License-Identifier: Apache-2.0
// WebrtcPeer: the offer is read first (what it lacks is the viewer's mistake, a 400), then webrtcbin answers it on
// its own threads while the caller waits on promises and the gathering state, never past the deadline.
#include "stream/gst/webrtc_peer.h"

#include <gst/sdp/sdp.h>
#include <gst/video/video.h>
#define GST_USE_UNSTABLE_API // webrtcbin's library is marked unstable in 1.22
#include <gst/webrtc/webrtc.h>

#include <cstring>

namespace overlayd {
namespace {

int64_t steadyMs()
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

struct SdpMessage {
    GstSDPMessage *message = nullptr;
    ~SdpMessage()
    {
        if (message != nullptr)
            gst_sdp_message_free(message);
    }
};

// "96 H264/90000" -> 96 when the encoding is H264.
int h264Format(const char *rtpmap)
{
    char name[16] = {};
    int type = -1;
    if (std::sscanf(rtpmap, "%d %15[^/]", &type, name) == 2 && g_ascii_strcasecmp(name, "H264") == 0)
        return type;
    return -1;
}

// The fmtp line of payload `type`, empty when none.
std::string fmtpOf(const GstSDPMedia *media, int type)
{
    for (guint i = 0; const char *fmtp = gst_sdp_media_get_attribute_val_n(media, "fmtp", i); ++i)
        if (std::atoi(fmtp) == type)
            return fmtp;
    return {};
}

// The MediaStream id the answer gives the video (a=msid): the page's <video> plays the stream it names.
constexpr const char *kWebrtcStreamId = "overlayd";

void markGathered(std::mutex &mutex, std::condition_variable &changed, bool &gathered)
{
    std::lock_guard lock(mutex);
    gathered = true;
    changed.notify_all();
}

} // namespace

Result<int> offeredH264PayloadType(const std::string &offer)
{
    if (offer.rfind("v=0", 0) != 0)
        return makeError(ErrorCode::Malformed, "the offer is not SDP: it must start with \"v=0\"");
    SdpMessage sdp;
    if (gst_sdp_message_new_from_text(offer.c_str(), &sdp.message) != GST_SDP_OK)
        return makeError(ErrorCode::Malformed, "the offer is not SDP");
    const GstSDPMedia *video = nullptr;
    for (guint i = 0; i < gst_sdp_message_medias_len(sdp.message) && !video; ++i)
        if (const GstSDPMedia *media = gst_sdp_message_get_media(sdp.message, i);
            g_strcmp0(gst_sdp_media_get_media(media), "video") == 0)
            video = media;
    if (video == nullptr)
        return makeError(ErrorCode::Malformed, "the offer has no m=video section: only video is sent");
    int chosen = -1, anyH264 = -1;
    for (guint i = 0; const char *rtpmap = gst_sdp_media_get_attribute_val_n(video, "rtpmap", i); ++i) {
        const int type = h264Format(rtpmap);
        if (type < 0)
            continue;
        anyH264 = type;
        const std::string fmtp = fmtpOf(video, type);
        if (fmtp.find("packetization-mode=1") == std::string::npos)
            continue;
        const bool baseline = fmtp.find("profile-level-id=42e0") != std::string::npos ||
                              fmtp.find("profile-level-id=4200") != std::string::npos;
        if (chosen < 0 || baseline)
            chosen = type;
        if (baseline)
            break;
    }
    if (chosen >= 0)
        return chosen;
    if (anyH264 >= 0)
        return makeError(ErrorCode::Malformed, "the offer's H.264 has no packetization-mode=1 (non-interleaved), the "
                                               "one mode sent");
    return makeError(ErrorCode::Malformed, "the offer's m=video has no H.264 (a=rtpmap:N H264/90000): the stream "
                                           "is H.264");
}

WebrtcPeer::WebrtcPeer(std::string id, std::string address, std::function<void()> requestKeyframe)
    : id_(std::move(id)), address_(std::move(address)), requestKeyframe_(requestKeyframe),
      feed_(std::move(requestKeyframe)), heardAtMs_(steadyMs())
{}

WebrtcPeer::~WebrtcPeer()
{
    feed_.detach();
    if (webrtc_ != nullptr)
        g_signal_handlers_disconnect_by_data(webrtc_, this);
    if (rtpbin_ != nullptr) {
        g_signal_handlers_disconnect_by_data(rtpbin_, this);
        gst_object_unref(rtpbin_);
    }
    branch_.drop();
}

Result<GstStructure *> WebrtcPeer::call(const char *signal, gpointer argument,
                                        std::chrono::steady_clock::time_point deadline)
{
    {
        std::lock_guard lock(mutex_);
        replied_ = false;
    }
    GstPromise *promise = gst_promise_new_with_change_func(
        [](GstPromise *, gpointer self) {
            auto *peer = static_cast<WebrtcPeer *>(self);
            std::lock_guard lock(peer->mutex_);
            peer->replied_ = true;
            peer->changed_.notify_all();
        },
        this, nullptr);
    g_signal_emit_by_name(webrtc_, signal, argument, promise);
    bool replied = false;
    {
        std::unique_lock lock(mutex_);
        replied = changed_.wait_until(lock, deadline, [&] { return replied_; });
    }
    if (!replied) { // interrupted: a late reply calls nothing, and the peer may go
        gst_promise_interrupt(promise);
        gst_promise_unref(promise);
        return makeError(ErrorCode::DeviceLost, std::string("webrtcbin did not answer ") + signal + " in time");
    }
    const GstStructure *reply =
        gst_promise_wait(promise) == GST_PROMISE_RESULT_REPLIED ? gst_promise_get_reply(promise) : nullptr;
    GstStructure *copy = reply ? gst_structure_copy(reply) : nullptr;
    gst_promise_unref(promise);
    GError *error = nullptr;
    if (copy != nullptr && gst_structure_get(copy, "error", G_TYPE_ERROR, &error, nullptr) && error) {
        std::string message = error->message;
        g_clear_error(&error);
        gst_structure_free(copy);
        return makeError(ErrorCode::Malformed, "webrtcbin refused the offer (" + std::string(signal) + "): " + message);
    }
    return copy;
}

Status WebrtcPeer::step(const char *signal, gpointer argument, std::chrono::steady_clock::time_point deadline)
{
    auto reply = call(signal, argument, deadline);
    if (!reply)
        return reply.error();
    if (*reply != nullptr)
        gst_structure_free(*reply);
    return Ok{};
}

Result<std::string> WebrtcPeer::negotiate(GMainContext *context, const WebrtcOptions &options, const std::string &offer,
                                          std::chrono::steady_clock::time_point deadline)
{
    auto payload = offeredH264PayloadType(offer);
    if (!payload)
        return payload.error();
    GstSDPMessage *sdp = nullptr;
    gst_sdp_message_new_from_text(offer.c_str(), &sdp);
    GstWebRTCSessionDescription *remote = gst_webrtc_session_description_new(GST_WEBRTC_SDP_TYPE_OFFER, sdp);

    const std::string pt = std::to_string(*payload);
    // Known before the answer, so that it carries a=ssrc lines with the stream's msid (below).
    const std::string ssrc = std::to_string(g_random_int());
    const std::string description =
        "appsrc name=src is-live=true format=time block=false ! h264parse ! rtph264pay config-interval=-1 "
        "aggregate-mode=zero-latency pt=" +
        pt + " ssrc=" + ssrc + " ! application/x-rtp,media=video,encoding-name=H264,clock-rate=90000,payload=" + pt +
        ",ssrc=(uint)" + ssrc + " ! webrtcbin name=webrtc bundle-policy=max-bundle";
    GError *error = nullptr;
    branch_.pipeline = gst_parse_launch(description.c_str(), &error);
    if (branch_.pipeline == nullptr || error != nullptr) {
        std::string why = error ? error->message : "?";
        g_clear_error(&error);
        gst_webrtc_session_description_free(remote);
        if (branch_.pipeline != nullptr)
            gst_object_unref(branch_.pipeline), branch_.pipeline = nullptr;
        return makeError(ErrorCode::NotFound, "the WebRTC pipeline cannot be made (" + why +
                                                  "; Debian: gstreamer1.0-plugins-bad, gstreamer1.0-nice)");
    }
    webrtc_ = gst_bin_get_by_name(GST_BIN(branch_.pipeline), "webrtc");
    gst_object_unref(webrtc_); // the pipeline holds it
    for (const std::string &server : options.iceServers) {
        if (server.rfind("stun://", 0) == 0) {
            g_object_set(webrtc_, "stun-server", server.c_str(), nullptr);
        } else {
            gboolean added = FALSE;
            g_signal_emit_by_name(webrtc_, "add-turn-server", server.c_str(), &added);
        }
    }
    g_signal_connect(webrtc_, "notify::ice-gathering-state", G_CALLBACK(&WebrtcPeer::onGatheringState), this);
    g_signal_connect(webrtc_, "notify::connection-state", G_CALLBACK(&WebrtcPeer::onConnectionState), this);
    // A viewer that vanishes without DELETE (a closed tab, a pulled cable) stops sending RTCP: kWebrtcSilenceMs
    // after its last report the peer is reaped (failed()); its source in webrtcbin's rtpbin timing out (RTCP's five
    // report intervals) or saying BYE ends it too.
    if (GstElement *rtpbin = gst_bin_get_by_name(GST_BIN(webrtc_), "rtpbin")) {
        rtpbin_ = rtpbin;
        g_signal_connect(rtpbin, "on-ssrc-active", G_CALLBACK(&WebrtcPeer::onViewerReport), this);
        g_signal_connect(rtpbin, "on-timeout", G_CALLBACK(&WebrtcPeer::onViewerGone), this);
        g_signal_connect(rtpbin, "on-bye-ssrc", G_CALLBACK(&WebrtcPeer::onViewerGone), this);
    }
    GstElement *appsrc = gst_bin_get_by_name(GST_BIN(branch_.pipeline), "src");
    gst_object_unref(appsrc); // the pipeline holds it
    GstPad *pad = gst_element_get_static_pad(appsrc, "src");
    gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_EVENT_UPSTREAM, &WebrtcPeer::onUpstreamEvent, this, nullptr);
    gst_object_unref(pad);
    branch_.watch(
        context,
        [](GstBus *, GstMessage *message, gpointer self) -> gboolean {
            if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR)
                static_cast<WebrtcPeer *>(self)->failed_ = true;
            return G_SOURCE_CONTINUE;
        },
        this);
    if (gst_element_set_state(branch_.pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
        gst_webrtc_session_description_free(remote);
        return makeError(ErrorCode::NotFound, "the WebRTC pipeline does not start (Debian: gstreamer1.0-nice)");
    }
    // The viewer only receives: the one transceiver sends. Its stream is named (a=msid, with a=ssrc lines): a
    // browser delivers the frames of an unnamed one to no track, though it decodes them.
    if (GstPad *sink = gst_element_get_static_pad(webrtc_, "sink_0")) {
        g_object_set(sink, "msid", kWebrtcStreamId, nullptr);
        GstWebRTCRTPTransceiver *transceiver = nullptr;
        g_object_get(sink, "transceiver", &transceiver, nullptr);
        if (transceiver != nullptr) {
            // NACKs answered from rtpbin's retransmission buffer (RTX), when the viewer offers them
            g_object_set(transceiver, "direction", GST_WEBRTC_RTP_TRANSCEIVER_DIRECTION_SENDONLY, "do-nack", TRUE,
                         nullptr);
            gst_object_unref(transceiver);
        }
        gst_object_unref(sink);
    }

    auto remoteSet = step("set-remote-description", remote, deadline);
    gst_webrtc_session_description_free(remote);
    if (!remoteSet)
        return remoteSet.error();
    auto created = call("create-answer", nullptr, deadline);
    if (!created)
        return created.error();
    GstWebRTCSessionDescription *answer = nullptr;
    if (*created) {
        gst_structure_get(*created, "answer", GST_TYPE_WEBRTC_SESSION_DESCRIPTION, &answer, nullptr);
        gst_structure_free(*created);
    }
    if (answer == nullptr)
        return makeError(ErrorCode::Malformed, "webrtcbin made no answer to the offer");
    auto localSet = step("set-local-description", answer, deadline);
    gst_webrtc_session_description_free(answer);
    if (!localSet)
        return localSet.error();
    feed_.attach(appsrc); // from the next keyframe, asked for now

    GstWebRTCICEGatheringState gathering = GST_WEBRTC_ICE_GATHERING_STATE_NEW;
    g_object_get(webrtc_, "ice-gathering-state", &gathering, nullptr);
    if (gathering == GST_WEBRTC_ICE_GATHERING_STATE_COMPLETE)
        markGathered(mutex_, changed_, gathered_);
    {
        std::unique_lock lock(mutex_);
        if (!changed_.wait_until(lock, deadline, [this] { return gathered_; }))
            return makeError(ErrorCode::DeviceLost, "ICE gathering did not complete in time");
    }
    GstWebRTCSessionDescription *local = nullptr;
    g_object_get(webrtc_, "local-description", &local, nullptr);
    if (local == nullptr)
        return makeError(ErrorCode::DeviceLost, "webrtcbin has no local description");
    gchar *text = gst_sdp_message_as_text(local->sdp);
    std::string out = text;
    g_free(text);
    gst_webrtc_session_description_free(local);
    return out;
}

void WebrtcPeer::onGatheringState(GstElement *webrtc, GParamSpec *, gpointer data)
{
    auto *self = static_cast<WebrtcPeer *>(data);
    GstWebRTCICEGatheringState state = GST_WEBRTC_ICE_GATHERING_STATE_NEW;
    g_object_get(webrtc, "ice-gathering-state", &state, nullptr);
    if (state == GST_WEBRTC_ICE_GATHERING_STATE_COMPLETE)
        markGathered(self->mutex_, self->changed_, self->gathered_);
}

void WebrtcPeer::onConnectionState(GstElement *webrtc, GParamSpec *, gpointer data)
{
    auto *self = static_cast<WebrtcPeer *>(data);
    GstWebRTCPeerConnectionState state = GST_WEBRTC_PEER_CONNECTION_STATE_NEW;
    g_object_get(webrtc, "connection-state", &state, nullptr);
    if (state == GST_WEBRTC_PEER_CONNECTION_STATE_CONNECTED)
        self->requestKeyframe_(); // what went before DTLS was up never reached the viewer
    if (state == GST_WEBRTC_PEER_CONNECTION_STATE_FAILED || state == GST_WEBRTC_PEER_CONNECTION_STATE_CLOSED)
        self->failed_ = true;
}

void WebrtcPeer::onViewerGone(GstElement *, guint, guint, gpointer data)
{
    static_cast<WebrtcPeer *>(data)->failed_ = true;
}

void WebrtcPeer::onViewerReport(GstElement *, guint, guint, gpointer data)
{
    static_cast<WebrtcPeer *>(data)->heardAtMs_ = steadyMs();
}

bool WebrtcPeer::failed() const
{
    return failed_ || steadyMs() - heardAtMs_ > kWebrtcSilenceMs;
}

GstPadProbeReturn WebrtcPeer::onUpstreamEvent(GstPad *, GstPadProbeInfo *info, gpointer data)
{
    GstEvent *event = GST_PAD_PROBE_INFO_EVENT(info);
    if (event != nullptr && gst_video_event_is_force_key_unit(event)) // a PLI or FIR from the viewer
        static_cast<WebrtcPeer *>(data)->requestKeyframe_();
    return GST_PAD_PROBE_OK;
}

} // namespace overlayd
