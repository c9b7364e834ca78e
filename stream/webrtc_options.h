// SPDX-License-Identifier: Apache-2.0
// What a user configures of WebRTC ([webrtc]): the peers that watch the one encode over WHEP. Plain data, header-only
// (the module shares it with the binary).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace overlayd {

// Limits of [webrtc] and of WHEP (docs/config.md "Limits").
inline constexpr unsigned kMaxWebrtcPeers = 64;   // [webrtc] max_peers at most: each peer packetizes and encrypts
inline constexpr size_t kMaxIceServers = 8;       // [webrtc] ice_servers entries
inline constexpr size_t kMaxIceServerBytes = 512; // one ice_servers entry
// How long POST /whep waits for the answer (ICE gathering included): the HTTP server's thread waits with it.
inline constexpr std::chrono::milliseconds kWhepAnswerTimeout{3000};

struct WebrtcOptions {
    bool enabled = false;
    // "stun://host:port" (one at most), "turn://user:password@host:port", "turns://...": none, host candidates only
    std::vector<std::string> iceServers;
    unsigned maxPeers = 8;

    bool operator==(const WebrtcOptions &) const = default;
};

} // namespace overlayd
