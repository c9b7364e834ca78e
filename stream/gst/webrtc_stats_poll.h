// SPDX-License-Identifier: Apache-2.0
// WebrtcStatsPoll: a peer's statistics from webrtcbin's get-stats promise. request() only emits the signal (on the
// engine's loop); the reply arrives on webrtcbin's thread and is kept behind a mutex in a block the promise shares,
// so a reply that comes after the peer went touches nothing of it.
#pragma once

#include <gst/gst.h>

#include <memory>
#include <mutex>

#include "stream/webrtc_peer_stats.h"

namespace overlayd {

// How often the engine's loop asks every peer's webrtcbin for its statistics: RTCP reports come about every
// second or more, so polling faster shows nothing new.
inline constexpr guint kWebrtcStatsMs = 2000;

class WebrtcStatsPoll
{
public:
    WebrtcStatsPoll();

    // Asks `webrtc` (a webrtcbin) for its statistics; never blocks.
    void request(GstElement *webrtc);
    // The last reply's figures (zeros and rtt -1 before the first).
    WebrtcPeerStats latest() const;

private:
    struct Shared {
        std::mutex mutex;
        WebrtcPeerStats stats;
    };
    static void onReply(GstPromise *promise, gpointer shared);

    std::shared_ptr<Shared> shared_;
};

// The figures of one get-stats reply: its "outbound-rtp" entries' packets-sent, nack-count and pli-count summed, and
// its "remote-inbound-rtp" round-trip-time.
WebrtcPeerStats parseWebrtcStats(const GstStructure *reply);

} // namespace overlayd
