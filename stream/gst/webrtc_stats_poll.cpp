// SPDX-License-Identifier: Apache-2.0
// WebrtcStatsPoll: each promise holds its own reference to the shared block (freed by the promise's destroy
// notify), so the peer may go while a request is still queued in webrtcbin.
#include "stream/gst/webrtc_stats_poll.h"

#define GST_USE_UNSTABLE_API // webrtcbin's library is marked unstable in 1.22
#include <gst/webrtc/webrtc.h>

namespace overlayd {
namespace {

// A numeric field whatever its integer or floating type (they differ between GStreamer releases), or `fallback`.
double numberField(const GstStructure *entry, const char *name, double fallback)
{
    const GValue *value = gst_structure_get_value(entry, name);
    if (value == nullptr || !g_value_type_transformable(G_VALUE_TYPE(value), G_TYPE_DOUBLE))
        return fallback;
    GValue number = G_VALUE_INIT;
    g_value_init(&number, G_TYPE_DOUBLE);
    g_value_transform(value, &number);
    const double out = g_value_get_double(&number);
    g_value_unset(&number);
    return out;
}

gboolean addEntry(GQuark, const GValue *value, gpointer data)
{
    auto *stats = static_cast<WebrtcPeerStats *>(data);
    if (!GST_VALUE_HOLDS_STRUCTURE(value))
        return TRUE;
    const GstStructure *entry = gst_value_get_structure(value);
    GstWebRTCStatsType type{};
    if (!gst_structure_get(entry, "type", GST_TYPE_WEBRTC_STATS_TYPE, &type, nullptr))
        return TRUE;
    if (type == GST_WEBRTC_STATS_OUTBOUND_RTP) {
        stats->packetsSent += uint64_t(numberField(entry, "packets-sent", 0));
        stats->nacks += uint64_t(numberField(entry, "nack-count", 0));
        stats->plis += uint64_t(numberField(entry, "pli-count", 0));
    }
    if (type == GST_WEBRTC_STATS_REMOTE_INBOUND_RTP)
        stats->rttS = numberField(entry, "round-trip-time", stats->rttS);
    return TRUE;
}

} // namespace

WebrtcPeerStats parseWebrtcStats(const GstStructure *reply)
{
    WebrtcPeerStats stats;
    if (reply != nullptr)
        gst_structure_foreach(reply, &addEntry, &stats);
    return stats;
}

WebrtcStatsPoll::WebrtcStatsPoll() : shared_(std::make_shared<Shared>()) {}

void WebrtcStatsPoll::request(GstElement *webrtc)
{
    GstPromise *promise =
        gst_promise_new_with_change_func(&WebrtcStatsPoll::onReply, new std::shared_ptr<Shared>(shared_),
                                         [](gpointer held) { delete static_cast<std::shared_ptr<Shared> *>(held); });
    g_signal_emit_by_name(webrtc, "get-stats", nullptr, promise); // webrtcbin keeps its own reference until done
    gst_promise_unref(promise);
}

void WebrtcStatsPoll::onReply(GstPromise *promise, gpointer held)
{
    if (gst_promise_wait(promise) != GST_PROMISE_RESULT_REPLIED)
        return; // interrupted: the pipeline stopped
    const WebrtcPeerStats stats = parseWebrtcStats(gst_promise_get_reply(promise));
    Shared &shared = **static_cast<std::shared_ptr<Shared> *>(held);
    std::lock_guard lock(shared.mutex);
    shared.stats = stats;
}

WebrtcPeerStats WebrtcStatsPoll::latest() const
{
    std::lock_guard lock(shared_->mutex);
    return shared_->stats;
}

} // namespace overlayd
