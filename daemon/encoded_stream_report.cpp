// SPDX-License-Identifier: Apache-2.0
// EncodedStreamReport: the encoder, the encoded sinks and the stage latencies for /state and /metrics.
#include "daemon/encoded_stream_report.h"

#include <ctime>

#include "control/status_report.h"

namespace overlayd {
namespace {

// "2026-11-27T15:20:59Z": when a client connected, in UTC.
std::string utcText(std::chrono::system_clock::time_point when)
{
    const std::time_t seconds = std::chrono::system_clock::to_time_t(when);
    std::tm parts{};
    gmtime_r(&seconds, &parts);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
    return text;
}

// Every stage's histogram, capture first: "blended", then the engine's.
std::vector<std::pair<std::string, LatencyHistogram>> stages(const EncodedStreamState &state)
{
    std::vector<std::pair<std::string, LatencyHistogram>> all{{"blended", state.blended}};
    all.insert(all.end(), state.engine.latency.begin(), state.engine.latency.end());
    return all;
}

// A WebRTC sink's peers with their RTCP figures (rtt_s null before the first receiver report).
nlohmann::json webrtcPeers(const std::vector<WebrtcPeerState> &peers)
{
    nlohmann::json out = nlohmann::json::array();
    for (const WebrtcPeerState &peer : peers)
        out.push_back({{"id", peer.id},
                       {"address", peer.address},
                       {"transport", "webrtc"},
                       {"since", utcText(peer.since)},
                       {"packets_sent", peer.stats.packetsSent},
                       {"nacks", peer.stats.nacks},
                       {"plis", peer.stats.plis},
                       {"rtt_s", peer.stats.rttS >= 0 ? nlohmann::json(peer.stats.rttS) : nlohmann::json()}});
    return out;
}

void reportWebrtcTotals(StatusReport &report, const EncodedSinkState &sink)
{
    const WebrtcPeerStats &totals = sink.peerTotals;
    report.metric("overlayd_webrtc_peers", "gauge", "WebRTC (WHEP) viewers connected.", double(sink.peers.size()));
    report.metric("overlayd_webrtc_packets_sent_total", "counter",
                  "RTP packets sent to WebRTC viewers (departed ones included), as webrtcbin counts them.",
                  double(totals.packetsSent));
    report.metric("overlayd_webrtc_nacks_total", "counter", "NACKs WebRTC viewers sent (RTCP feedback).",
                  double(totals.nacks));
    report.metric("overlayd_webrtc_plis_total", "counter", "Picture loss indications WebRTC viewers sent.",
                  double(totals.plis));
}

} // namespace

void EncodedStreamReport::report(StatusReport &report) const
{
    if (!running_)
        return;
    const EncodedStreamState state = running_->state();
    const EngineState &engine = state.engine;
    nlohmann::json sinks = nlohmann::json::array();
    for (const EncodedSinkState &sink : engine.sinks) {
        nlohmann::json clients = nlohmann::json::array();
        for (const RtspClientState &client : sink.clients)
            clients.push_back(
                {{"address", client.address}, {"transport", client.transport}, {"since", utcText(client.since)}});
        nlohmann::json entry = {{"kind", sink.kind}, {"sink", sink.key}, {"url", sink.describe}};
        if (sink.kind == "rtsp")
            entry.update({{"clients", clients},
                          {"pending_shed", sink.pendingShed},
                          {"pending_timed_out", sink.pendingTimedOut}});
        if (sink.kind == "webrtc")
            entry["peers"] = webrtcPeers(sink.peers);
        if (sink.kind == "record")
            entry.update({{"current_file", sink.currentFile},
                          {"segments", sink.segments},
                          {"bytes", sink.bytes},
                          {"oldest", sink.oldest},
                          {"deleted", sink.deleted},
                          {"disk_full", sink.diskFull},
                          {"disk_full_stops", sink.diskFullStops}});
        if (sink.kind == "push")
            entry.update({{"connected", sink.connected}, {"reconnects", sink.reconnects}});
        if (sink.kind != "rtsp")
            entry.update({{"last_error", sink.lastError}, {"dropped", sink.dropped}});
        sinks.push_back(std::move(entry));
    }
    nlohmann::json latency = nlohmann::json::object();
    for (const auto &[stage, histogram] : stages(state))
        latency[stage] = {{"frames", histogram.count},
                          {"p50_s", histogram.quantile(0.5)},
                          {"p99_s", histogram.quantile(0.99)},
                          {"mean_s", histogram.count ? histogram.sum / double(histogram.count) : 0.0}};
    report.set("encoder", {{"running", engine.running},
                           {"latency", latency},
                           {"element", engine.encoder},
                           {"device", engine.device},
                           {"frames_in", engine.framesIn},
                           {"frames_encoded", engine.framesEncoded},
                           {"keyframes", engine.keyframes},
                           {"bytes", engine.bytesEncoded},
                           {"bitrate_kbps", engine.bitrateKbps},
                           {"frames_copied", state.feed.copied},
                           {"frames_zero_copy", state.feed.zeroCopy},
                           {"dmabuf_import", engine.dmabufImport},
                           {"frames_converted", state.feed.converted},
                           {"frames_dropped", state.feed.dropped},
                           {"sinks", sinks}});

    const std::string label = StatusReport::label("element", engine.encoder);
    report.metric("overlayd_encoders", "gauge", "Encoders running (one encode is shared by every encoded sink).",
                  engine.running ? 1.0 : 0.0, label);
    report.metric("overlayd_encoder_frames_total", "counter", "Frames the encoder took.", double(engine.framesIn),
                  label);
    report.metric("overlayd_encoder_encoded_frames_total", "counter", "Access units out of the encoder.",
                  double(engine.framesEncoded), label);
    report.metric("overlayd_encoder_keyframes_total", "counter", "Keyframes (IDR) out of the encoder.",
                  double(engine.keyframes), label);
    report.metric("overlayd_encoder_bytes_total", "counter", "Bytes out of the encoder.", double(engine.bytesEncoded),
                  label);
    report.metric("overlayd_encoder_bitrate_kbps", "gauge", "Encoded bitrate over the last second, kbit/s.",
                  engine.bitrateKbps, label);
    report.metric("overlayd_encoder_dropped_total", "counter",
                  "Frames dropped before the encoder (every slot still with it).", double(state.feed.dropped), label);
    report.metric("overlayd_encoder_converted_total", "counter",
                  "Frames converted to I420 on their one copy for the encoder.", double(state.feed.converted), label);
    report.metric("overlayd_encoder_copied_total", "counter", "Frames copied for the encoder.",
                  double(state.feed.copied), label);
    report.metric("overlayd_encoder_zero_copy_total", "counter",
                  "Frames the encoder took as the capture buffer's DMABUF, not copied.", double(state.feed.zeroCopy),
                  label);
    for (const EncodedSinkState &sink : engine.sinks) {
        const std::string sinkLabel =
            StatusReport::label("sink", sink.key) + "," + StatusReport::label("url", sink.describe);
        if (sink.kind == "webrtc")
            reportWebrtcTotals(report, sink);
        if (sink.kind == "rtsp") {
            report.metric("overlayd_rtsp_clients", "gauge", "Clients connected to an RTSP sink.",
                          double(sink.clients.size()), sinkLabel);
            const char *limitHelp = "RTSP connections closed before they asked to play, by the limit that closed them.";
            report.sample("overlayd_rtsp_limit_total", "counter", limitHelp, "overlayd_rtsp_limit_total",
                          double(sink.pendingShed), sinkLabel + "," + StatusReport::label("limit", "pending"));
            report.sample("overlayd_rtsp_limit_total", "counter", limitHelp, "overlayd_rtsp_limit_total",
                          double(sink.pendingTimedOut),
                          sinkLabel + "," + StatusReport::label("limit", "play_deadline"));
        }
        if (sink.kind == "record") {
            report.metric("overlayd_record_segments", "gauge", "Finished segments in a recording's folder.",
                          double(sink.segments), sinkLabel);
            report.metric("overlayd_record_bytes", "gauge", "Bytes of a recording's finished segments.",
                          double(sink.bytes), sinkLabel);
            report.metric("overlayd_record_deleted_total", "counter", "Segments retention deleted.",
                          double(sink.deleted), sinkLabel);
            report.metric("overlayd_record_disk_full", "gauge", "1 while a recording waits for disk space.",
                          sink.diskFull ? 1.0 : 0.0, sinkLabel);
            report.metric("overlayd_record_disk_full_total", "counter", "Times a full disk stopped a recording.",
                          double(sink.diskFullStops), sinkLabel);
        }
        if (sink.kind == "push") {
            report.metric("overlayd_push_connected", "gauge", "1 while a push's server takes the stream.",
                          sink.connected ? 1.0 : 0.0, sinkLabel);
            report.metric("overlayd_push_reconnects_total", "counter", "Connection attempts after a push's first.",
                          double(sink.reconnects), sinkLabel);
        }
        if (sink.kind != "rtsp")
            report.metric("overlayd_encoded_sink_dropped_total", "counter",
                          "Access units a recording or push dropped while behind or not running.", double(sink.dropped),
                          sinkLabel);
    }

    const std::string family = "overlayd_stage_latency_seconds";
    const char *help = "Seconds from a frame's capture to a stage of the encoded path.";
    for (const auto &[stage, histogram] : stages(state)) {
        const std::string stageLabel = StatusReport::label("stage", stage);
        uint64_t cumulative = 0;
        for (size_t i = 0; i <= LatencyHistogram::kBounds.size(); ++i) {
            cumulative += histogram.counts[i];
            const std::string bound = i < LatencyHistogram::kBounds.size()
                                          ? nlohmann::json(LatencyHistogram::kBounds[i]).dump()
                                          : std::string("+Inf");
            report.sample(family, "histogram", help, family + "_bucket", double(cumulative),
                          stageLabel + ",le=\"" + bound + "\"");
        }
        report.sample(family, "histogram", help, family + "_sum", histogram.sum, stageLabel);
        report.sample(family, "histogram", help, family + "_count", double(histogram.count), stageLabel);
    }
}

} // namespace overlayd
