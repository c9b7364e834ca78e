// SPDX-License-Identifier: Apache-2.0
// WebrtcPeer: one WHEP viewer. Its own pipeline, fed the encoder's access units through a BranchFeed:
//
//   appsrc ! h264parse ! rtph264pay config-interval=-1 aggregate-mode=zero-latency pt=<the offer's>
//     ! application/x-rtp,... ! webrtcbin bundle-policy=max-bundle (host candidates unless ice_servers are given)
//
// negotiate() answers the offer and returns once ICE gathering is complete, so the answer carries every candidate
// (no trickle). A keyframe is asked for when the feed attaches, when DTLS is up, and for every PLI/FIR the viewer
// sends (webrtcbin turns them into upstream force-key-unit events, caught at the appsrc).
#pragma once

#include <gst/gst.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>

#include "base/result.h"
#include "stream/gst/branch_feed.h"
#include "stream/gst/branch_pipeline.h"
#include "stream/gst/webrtc_stats_poll.h"
#include "stream/webrtc_options.h"

namespace overlayd {

class WebrtcPeer
{
public:
    WebrtcPeer(std::string id, std::string address, std::function<void()> requestKeyframe);
    ~WebrtcPeer();
    WebrtcPeer(const WebrtcPeer &) = delete;
    WebrtcPeer &operator=(const WebrtcPeer &) = delete;

    // Builds the pipeline on `context` and answers `offer` (the SDP answer with candidates), by `deadline`.
    Result<std::string> negotiate(GMainContext *context, const WebrtcOptions &options, const std::string &offer,
                                  std::chrono::steady_clock::time_point deadline);
    // On the encoder's streaming thread; never blocks.
    bool push(GstSample *sample) { return feed_.push(sample); }
    // ICE or DTLS failed, the viewer closed, or its reports stopped (kWebrtcSilenceMs): the peer is to be reaped.
    bool failed() const;
    // On the engine's loop, once negotiated: asks webrtcbin for its statistics (stats() has them a moment later).
    void pollStats() { stats_.request(webrtc_); }
    WebrtcPeerStats stats() const { return stats_.latest(); }

    const std::string &id() const { return id_; }
    const std::string &address() const { return address_; }
    std::chrono::system_clock::time_point since() const { return since_; }

private:
    // A webrtcbin action signal whose promise is waited for (until `deadline`): its reply, or the error.
    Result<GstStructure *> call(const char *signal, gpointer argument, std::chrono::steady_clock::time_point deadline);
    // call() when the reply says nothing but whether it worked.
    Status step(const char *signal, gpointer argument, std::chrono::steady_clock::time_point deadline);
    static void onGatheringState(GstElement *, GParamSpec *, gpointer self);
    static void onConnectionState(GstElement *, GParamSpec *, gpointer self);
    static void onViewerGone(GstElement *, guint session, guint ssrc, gpointer self);
    static void onViewerReport(GstElement *, guint session, guint ssrc, gpointer self);
    static GstPadProbeReturn onUpstreamEvent(GstPad *, GstPadProbeInfo *info, gpointer self);

    std::string id_, address_;
    std::chrono::system_clock::time_point since_ = std::chrono::system_clock::now();
    std::function<void()> requestKeyframe_;
    BranchFeed feed_;
    BranchPipeline branch_;
    GstElement *webrtc_ = nullptr; // in branch_'s pipeline
    GstElement *rtpbin_ = nullptr; // webrtcbin's own (a reference)
    std::atomic<bool> failed_{false};
    std::atomic<int64_t> heardAtMs_; // steady clock: the viewer's last RTCP report, or the peer's start
    WebrtcStatsPoll stats_;

    std::mutex mutex_; // guards the two below, signalled by webrtcbin's threads
    std::condition_variable changed_;
    bool replied_ = false;  // the promise of the call() under way
    bool gathered_ = false; // ICE gathering complete
};

// A viewer whose RTCP reports stop for this long is gone (a closed tab, a pulled cable), as ICE consent freshness
// would find (RFC 7675: 30 s), which webrtcbin 1.22 does not turn on. Browsers report every second, GStreamer's
// rtpbin every 5 s at most 7.5 s apart: two of its reports may go missing first.
inline constexpr int64_t kWebrtcSilenceMs = 15000;

// The payload type of the offer's first H.264 video format with packetization-mode=1 (constrained baseline
// preferred), or why the offer cannot be answered: "the offer is not SDP", "no m=video", "no H.264".
Result<int> offeredH264PayloadType(const std::string &offer);

} // namespace overlayd
