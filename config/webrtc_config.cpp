// SPDX-License-Identifier: Apache-2.0
// [webrtc]: the WHEP viewers of the one encode. Enabled alone it runs the encoder with [encoder]'s defaults (the
// [encoder] table is optional, as for an RTSP sink); it is served on the HTTP server, so it needs [http].
#include "config/config_sections.h"

namespace overlayd {

void readWebrtc(TableReader &root, bool httpEnabled, WebrtcOptions &out)
{
    auto table = root.table("webrtc");
    if (!table)
        return;
    if (!streamBuiltIn()) {
        root.problem("webrtc", "this overlayd was built without the encoded outputs (CMake option OVERLAYD_STREAM, "
                               "GStreamer): [webrtc] is not available");
        return;
    }
    if (auto enabled = table->boolean("enabled"))
        out.enabled = *enabled;
    if (auto servers = table->strings("ice_servers", kMaxIceServers)) {
        unsigned stun = 0;
        for (const std::string &server : *servers) {
            const bool known =
                server.rfind("stun://", 0) == 0 || server.rfind("turn://", 0) == 0 || server.rfind("turns://", 0) == 0;
            if (server.size() > kMaxIceServerBytes)
                table->problem("ice_servers",
                               "an entry is longer than " + std::to_string(kMaxIceServerBytes) + " bytes");
            else if (!known || server.find(':', server.find("://") + 3) == std::string::npos)
                table->problem("ice_servers", "'" + server +
                                                  "': \"stun://HOST:PORT\" or \"turn://USER:PASSWORD@HOST:PORT\" "
                                                  "(turns:// for TLS)");
            else if (server.rfind("stun://", 0) == 0 && ++stun > 1)
                table->problem("ice_servers", "'" + server + "': one STUN server at most");
        }
        out.iceServers = *servers;
    }
    if (auto peers = table->integer("max_peers", 1, kMaxWebrtcPeers))
        out.maxPeers = unsigned(*peers);
    if (out.enabled && !httpEnabled)
        table->problem("enabled", "WebRTC is offered over WHEP on the HTTP server: add an [http] table");
    table->finish();
}

} // namespace overlayd
