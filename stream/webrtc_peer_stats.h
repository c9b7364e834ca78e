// SPDX-License-Identifier: Apache-2.0
// What /state and /metrics show of a WebRTC peer: webrtcbin's own statistics (its get-stats), as RTCP reports them.
// Plain data, header-only: it crosses the stream module's boundary (encoded_stream_engine.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace overlayd {

struct WebrtcPeerStats {
    uint64_t packetsSent = 0; // RTP packets sent to the viewer (retransmissions included)
    uint64_t nacks = 0;       // NACK feedback messages the viewer sent (each asks for lost packets again)
    uint64_t plis = 0;        // picture loss indications the viewer sent (each asks for a keyframe)
    double rttS = -1.0;       // round-trip time from the viewer's receiver reports; -1 until one arrived

    WebrtcPeerStats &operator+=(const WebrtcPeerStats &other)
    {
        packetsSent += other.packetsSent;
        nacks += other.nacks;
        plis += other.plis;
        return *this;
    }
};

// One WHEP viewer.
struct WebrtcPeerState {
    std::string id;                              // the Location's last part: DELETE /whep/ID
    std::string address;                         // "127.0.0.1:50312", the WHEP request's
    std::chrono::system_clock::time_point since; // when it joined
    WebrtcPeerStats stats;                       // as of the last poll (kWebrtcStatsMs)
};

} // namespace overlayd
