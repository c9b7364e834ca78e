// SPDX-License-Identifier: Apache-2.0
// WebrtcPeers: a peer's pipeline is dropped outside the lock (setting webrtcbin to NULL joins its threads), and
// never on the encoder's streaming thread.
#include "stream/gst/webrtc_peers.h"

#include <algorithm>

#include "stream/gst/branch_pipeline.h"

namespace overlayd {

WebrtcPeers::WebrtcPeers(const WebrtcOptions &options, const EngineLog &log, std::function<void()> requestKeyframe)
    : options_(options), log_(log), requestKeyframe_(std::move(requestKeyframe))
{}

WebrtcPeers::~WebrtcPeers()
{
    stop();
}

void WebrtcPeers::start(GMainContext *context)
{
    std::lock_guard lock(mutex_);
    context_ = context;
    departed_ = {};
    ticks_ = 0;
    replaceTimer(timer_, context_, kWebrtcReapMs, &WebrtcPeers::onReap, this);
}

void WebrtcPeers::stop()
{
    std::vector<std::shared_ptr<WebrtcPeer>> gone;
    {
        std::lock_guard lock(mutex_);
        dropSource(timer_);
        context_ = nullptr;
        gone.swap(peers_);
    }
    gone.clear();
}

Result<WebrtcAnswer> WebrtcPeers::add(const std::string &offer, const std::string &address)
{
    const auto deadline = std::chrono::steady_clock::now() + kWhepAnswerTimeout;
    std::shared_ptr<WebrtcPeer> peer;
    GMainContext *context = nullptr;
    {
        std::lock_guard lock(mutex_);
        if (context_ == nullptr)
            return makeError(ErrorCode::TryAgain, "no stream yet: the encoder starts with the first frame");
        if (peers_.size() + pending_ >= options_.maxPeers)
            return makeError(ErrorCode::TryAgain,
                             "max_peers (" + std::to_string(options_.maxPeers) + ") are watching already");
        ++pending_;
        context = context_;
        peer = std::make_shared<WebrtcPeer>(std::to_string(nextId_++), address, requestKeyframe_);
    }
    auto answer = peer->negotiate(context, options_, offer, deadline);
    std::lock_guard lock(mutex_);
    --pending_;
    if (!answer)
        return answer.error(); // the peer goes here, on the caller's thread
    if (context_ != context)   // the engine closed meanwhile
        return makeError(ErrorCode::TryAgain, "the stream restarted: offer again");
    peers_.push_back(peer);
    log_(kLogInfo, "webrtc: peer " + peer->id() + " (" + address + ") joined");
    return WebrtcAnswer{peer->id(), std::move(*answer)};
}

Status WebrtcPeers::remove(const std::string &id)
{
    std::shared_ptr<WebrtcPeer> gone;
    {
        std::lock_guard lock(mutex_);
        const auto it = std::find_if(peers_.begin(), peers_.end(), [&](const auto &peer) { return peer->id() == id; });
        if (it == peers_.end())
            return makeError(ErrorCode::NotFound, "no WebRTC peer " + id);
        gone = *it;
        retire(gone);
        peers_.erase(it);
    }
    log_(kLogInfo, "webrtc: peer " + id + " hung up");
    return Ok{};
}

bool WebrtcPeers::push(GstSample *sample)
{
    std::lock_guard lock(mutex_);
    bool taken = false;
    for (const auto &peer : peers_)
        taken = peer->push(sample) || taken;
    return taken;
}

gboolean WebrtcPeers::onReap(gpointer data)
{
    auto *self = static_cast<WebrtcPeers *>(data);
    std::vector<std::shared_ptr<WebrtcPeer>> gone, polled;
    {
        std::lock_guard lock(self->mutex_);
        auto failed = std::stable_partition(self->peers_.begin(), self->peers_.end(),
                                            [](const auto &peer) { return !peer->failed(); });
        gone.assign(failed, self->peers_.end());
        self->peers_.erase(failed, self->peers_.end());
        for (const auto &peer : gone)
            self->retire(peer);
        if (++self->ticks_ % (kWebrtcStatsMs / kWebrtcReapMs) == 0)
            polled = self->peers_;
    }
    // get-stats only queues a task on webrtcbin's thread: the reply is kept by the peer when it comes.
    for (const auto &peer : polled)
        peer->pollStats();
    for (const auto &peer : gone)
        self->log_(kLogInfo, "webrtc: peer " + peer->id() + " (" + peer->address() +
                                 ") lost: its connection failed or its reports stopped");
    return G_SOURCE_CONTINUE;
}

EncodedSinkState WebrtcPeers::state() const
{
    EncodedSinkState out;
    out.kind = "webrtc";
    out.key = "webrtc";
    out.describe = "/whep";
    std::lock_guard lock(mutex_);
    out.peerTotals = departed_;
    for (const auto &peer : peers_) {
        const WebrtcPeerStats stats = peer->stats();
        out.peers.push_back({peer->id(), peer->address(), peer->since(), stats});
        out.peerTotals += stats;
    }
    return out;
}

void WebrtcPeers::retire(const std::shared_ptr<WebrtcPeer> &peer)
{
    departed_ += peer->stats();
}

} // namespace overlayd
