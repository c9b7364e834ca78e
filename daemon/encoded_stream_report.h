// The encoded outputs as /state and /metrics show them: the encoder (kind, device, measured bitrate, keyframes,
// frames dropped before it) and each encoded sink with its clients (address, transport, since).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "stream/encoded_stream.h"

namespace overlayd {

// /state's "encoder" object.
nlohmann::json encodedStreamJson(const stream::EncodedStreamState &state);
// /metrics' overlayd_encoder_* and overlayd_rtsp_* families, in the Prometheus text format.
std::string encodedStreamMetrics(const stream::EncodedStreamState &state);

} // namespace overlayd
