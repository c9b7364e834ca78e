// encodedStreamJson / encodedStreamMetrics: one place that names what the encoded outputs report.
#include "daemon/encoded_stream_report.h"

#include <ctime>

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

// One metric family's HELP and TYPE lines and its samples.
void family(std::string &text, const char *name, const char *type, const char *help,
            const std::vector<std::pair<std::string, double>> &samples)
{
    text += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
    for (const auto &[labels, value] : samples)
        text += std::string(name) + (labels.empty() ? "" : "{" + labels + "}") + " " +
                nlohmann::json(value).dump() + "\n";
}

// Every stage's histogram, capture first: "blended", then the engine's.
std::vector<std::pair<std::string, stream::LatencyHistogram>> stages(const stream::EncodedStreamState &state)
{
    std::vector<std::pair<std::string, stream::LatencyHistogram>> all{{"blended", state.blended}};
    all.insert(all.end(), state.engine.latency.begin(), state.engine.latency.end());
    return all;
}

} // namespace

nlohmann::json encodedStreamJson(const stream::EncodedStreamState &state)
{
    const stream::EngineState &engine = state.engine;
    nlohmann::json sinks = nlohmann::json::array();
    for (const stream::EncodedSinkState &sink : engine.sinks) {
        nlohmann::json clients = nlohmann::json::array();
        for (const stream::RtspClientState &client : sink.clients)
            clients.push_back(
                {{"address", client.address}, {"transport", client.transport}, {"since", utcText(client.since)}});
        sinks.push_back({{"sink", sink.key}, {"url", sink.describe}, {"clients", clients}});
    }
    nlohmann::json latency = nlohmann::json::object();
    for (const auto &[stage, histogram] : stages(state))
        latency[stage] = {{"frames", histogram.count},
                          {"p50_s", histogram.quantile(0.5)},
                          {"p99_s", histogram.quantile(0.99)},
                          {"mean_s", histogram.count ? histogram.sum / double(histogram.count) : 0.0}};
    return {{"running", engine.running},
            {"latency", latency},
            {"element", engine.encoder},
            {"device", engine.device},
            {"frames_in", engine.framesIn},
            {"frames_encoded", engine.framesEncoded},
            {"keyframes", engine.keyframes},
            {"bytes", engine.bytesEncoded},
            {"bitrate_kbps", engine.bitrateKbps},
            {"frames_copied", state.feed.copied},
            {"frames_converted", state.feed.converted},
            {"frames_dropped", state.feed.dropped},
            {"sinks", sinks}};
}

std::string encodedStreamMetrics(const stream::EncodedStreamState &state)
{
    const stream::EngineState &engine = state.engine;
    const std::string label = "element=" + nlohmann::json(engine.encoder).dump();
    std::string text;
    family(text, "overlayd_encoders", "gauge", "Encoders running (one encode is shared by every encoded sink).",
           {{label, engine.running ? 1.0 : 0.0}});
    family(text, "overlayd_encoder_frames_total", "counter", "Frames the encoder took.",
           {{label, double(engine.framesIn)}});
    family(text, "overlayd_encoder_encoded_frames_total", "counter", "Access units out of the encoder.",
           {{label, double(engine.framesEncoded)}});
    family(text, "overlayd_encoder_keyframes_total", "counter", "Keyframes (IDR) out of the encoder.",
           {{label, double(engine.keyframes)}});
    family(text, "overlayd_encoder_bytes_total", "counter", "Bytes out of the encoder.",
           {{label, double(engine.bytesEncoded)}});
    family(text, "overlayd_encoder_bitrate_kbps", "gauge", "Encoded bitrate over the last second, kbit/s.",
           {{label, engine.bitrateKbps}});
    family(text, "overlayd_encoder_dropped_total", "counter",
           "Frames dropped before the encoder (every slot still with it).", {{label, double(state.feed.dropped)}});
    family(text, "overlayd_encoder_converted_total", "counter",
           "Frames converted to I420 on their one copy for the encoder.", {{label, double(state.feed.converted)}});
    std::vector<std::pair<std::string, double>> clients;
    for (const stream::EncodedSinkState &sink : engine.sinks)
        clients.emplace_back("sink=" + nlohmann::json(sink.key).dump() + ",url=" + nlohmann::json(sink.describe).dump(),
                             double(sink.clients.size()));
    family(text, "overlayd_rtsp_clients", "gauge", "Clients connected to an RTSP sink.", clients);
    text += "# HELP overlayd_stage_latency_seconds Seconds from a frame's capture to a stage of the encoded path.\n"
            "# TYPE overlayd_stage_latency_seconds histogram\n";
    for (const auto &[stage, histogram] : stages(state)) {
        const std::string name = "overlayd_stage_latency_seconds";
        const std::string stageLabel = "stage=" + nlohmann::json(stage).dump();
        uint64_t cumulative = 0;
        for (size_t i = 0; i <= stream::LatencyHistogram::kBounds.size(); ++i) {
            cumulative += histogram.counts[i];
            const std::string bound = i < stream::LatencyHistogram::kBounds.size()
                                          ? nlohmann::json(stream::LatencyHistogram::kBounds[i]).dump()
                                          : std::string("+Inf");
            text += name + "_bucket{" + stageLabel + ",le=\"" + bound + "\"} " + std::to_string(cumulative) + "\n";
        }
        text += name + "_sum{" + stageLabel + "} " + nlohmann::json(histogram.sum).dump() + "\n";
        text += name + "_count{" + stageLabel + "} " + std::to_string(histogram.count) + "\n";
    }
    return text;
}

} // namespace overlayd
