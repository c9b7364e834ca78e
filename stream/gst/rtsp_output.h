// SPDX-License-Identifier: Apache-2.0
// RtspOutput: one kind = "rtsp" sink: a gst-rtsp-server on its address with one shared media at its path. The
// media's pipeline is an appsrc fed the encoder's access units (push()), so every client of the mount shares the
// one encode; RTP goes over UDP or TCP interleaved as the client asks. A new media starts at a keyframe, and every
// client that starts playing asks the encoder for one (requestKeyframe), so a late joiner sees a picture at once.
// Connections that have not reached PLAY are held to PendingClients' caps and deadline.
#pragma once

#include <gst/gst.h>
#include <gst/rtsp-server/rtsp-server.h>

#include <functional>
#include <map>
#include <mutex>

#include "base/result.h"
#include "stream/encoded_stream_engine.h"
#include "stream/gst/rtsp_access.h"
#include "stream/pending_clients.h"

namespace overlayd {

class RtspOutput
{
public:
    RtspOutput(const EncodedSinkOptions &options, const EngineLog &log, std::function<void()> requestKeyframe);
    ~RtspOutput();
    RtspOutput(const RtspOutput &) = delete;
    RtspOutput &operator=(const RtspOutput &) = delete;

    // Binds the address and serves from `context` (the engine's main loop); the bind's error names the address.
    Status start(GMainContext *context);
    // One access unit (with its caps); from the encoder's streaming thread. Dropped while no client plays (false).
    bool push(GstSample *sample);
    EncodedSinkState state() const;

private:
    static void onClientConnected(GstRTSPServer *, GstRTSPClient *client, RtspOutput *self);
    static void onClientClosed(GstRTSPClient *client, RtspOutput *self);
    static GstRTSPStatusCode onPreDescribe(GstRTSPClient *client, GstRTSPContext *context, RtspOutput *self);
    static void onSetup(GstRTSPClient *client, GstRTSPContext *context, RtspOutput *self);
    static void onPlay(GstRTSPClient *client, GstRTSPContext *context, RtspOutput *self);
    static void onMediaConfigure(GstRTSPMediaFactory *, GstRTSPMedia *media, RtspOutput *self);
    static void onMediaUnprepared(GstRTSPMedia *media, RtspOutput *self);
    // Once a second on the engine's loop: closes the connections that have not reached PLAY by the deadline.
    static gboolean onPendingTick(gpointer self);
    // Closes the clients `handles` names (from PendingClients), on the engine's loop, without the mutex held: a close
    // emits "closed" at once.
    void closeClients(const std::vector<PendingClients::Handle> &handles, const char *why);

    EncodedSinkOptions options_;
    EngineLog log_;
    std::function<void()> requestKeyframe_;
    GstRTSPServer *server_ = nullptr;
    GSource *source_ = nullptr;
    GSource *pendingTick_ = nullptr;
    RtspAccess access_;

    mutable std::mutex mutex_;
    GstElement *appsrc_ = nullptr;  // the shared media's, while one is prepared (a reference)
    GstRTSPMedia *media_ = nullptr; // its media (a reference), whose signal is ours to disconnect
    bool waitingForKeyframe_ = true;
    GstClockTime offset_ = GST_CLOCK_TIME_NONE; // the encoder's time of the media's first access unit
    std::map<GstRTSPClient *, RtspClientState> clients_;
    PendingClients pending_; // the clients_ that have not asked to play yet
};

} // namespace overlayd
