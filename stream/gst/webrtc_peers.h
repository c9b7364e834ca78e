// SPDX-License-Identifier: Apache-2.0
// WebrtcPeers: the WHEP viewers of one engine, at most max_peers. add() negotiates outside the lock (the encoder's
// thread keeps pushing to the others meanwhile); a timer on the engine's loop reaps the peers whose ICE or DTLS
// failed or closed, and polls their statistics.
#pragma once

#include <gst/gst.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "stream/encoded_stream_engine.h"
#include "stream/gst/webrtc_peer.h"

namespace overlayd {

// How often failed peers are looked for.
inline constexpr guint kWebrtcReapMs = 1000;

class WebrtcPeers
{
public:
    WebrtcPeers(const WebrtcOptions &options, const EngineLog &log, std::function<void()> requestKeyframe);
    ~WebrtcPeers();

    // From open(): peers may join, their pipelines watched on `context`. stop(): every peer hung up.
    void start(GMainContext *context);
    void stop();

    Result<WebrtcAnswer> add(const std::string &offer, const std::string &address);
    Status remove(const std::string &id);
    // On the encoder's streaming thread; never blocks. True when at least one peer took the access unit.
    bool push(GstSample *sample);
    EncodedSinkState state() const;

private:
    static gboolean onReap(gpointer self);
    // A peer leaving peers_: its last statistics join departed_ (the lock held).
    void retire(const std::shared_ptr<WebrtcPeer> &peer);

    WebrtcOptions options_;
    EngineLog log_;
    std::function<void()> requestKeyframe_;
    mutable std::mutex mutex_;
    GMainContext *context_ = nullptr;
    GSource *timer_ = nullptr;
    std::vector<std::shared_ptr<WebrtcPeer>> peers_;
    unsigned pending_ = 0; // negotiating: they count towards max_peers
    uint64_t nextId_ = 1;
    WebrtcPeerStats departed_; // the sums of the peers gone since start()
    unsigned ticks_ = 0;       // of the reap timer: every kWebrtcStatsMs of them, the peers' statistics are polled
};

} // namespace overlayd
