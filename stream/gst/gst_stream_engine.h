// SPDX-License-Identifier: Apache-2.0
// GstStreamEngine: the GStreamer implementation of EncodedStreamEngine. Its pipeline, for frames of one format:
//
//   appsrc "feed" (I420: the feed's slots wrapped, or the capture buffers' DMABUF) ! <encoder>
//     [! capsfilter profile] ! h264parse
//     ! tee "encoded" ─┬─ queue ! appsink "rtsp"  ─► RtspOutput::push ─► the shared media's appsrc ─► clients
//                      └─ (one branch per further encoded sink: record, push; one per WebRTC peer)
//
// GStreamer's main loop (the RTSP servers, the bus) runs on the engine's own thread, on its own GMainContext.
#pragma once

#include <gst/app/gstappsink.h>
#include <gst/gst.h>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "stream/encoded_stream_engine.h"
#include "stream/gst/encoded_output.h"
#include "stream/gst/rtsp_output.h"
#include "stream/gst/webrtc_peers.h"

namespace overlayd {

class GstStreamEngine : public EncodedStreamEngine
{
public:
    GstStreamEngine(const StreamOptions &options, const EngineLog &log);
    ~GstStreamEngine() override;

    Status open(const EngineFormat &format) override;
    void push(EncoderInput frame) override;
    void close() override;
    EngineState state() const override;
    Result<WebrtcAnswer> addPeer(const std::string &offer, const std::string &address) override;
    Status removePeer(const std::string &id) override;

private:
    Status build(const EngineFormat &format);
    // An upstream force-key-unit event to the encoder: the frame whose running time is `at` or later (the next
    // frame when `at` is none) is encoded as an IDR.
    void requestKeyframe(GstClockTime at = GST_CLOCK_TIME_NONE);
    static GstFlowReturn onEncoded(GstAppSink *sink, gpointer self);
    static gboolean onBusMessage(GstBus *, GstMessage *message, gpointer self);

    StreamOptions options_;
    EngineLog log_;
    EngineFormat format_{};
    GMainContext *context_ = nullptr;
    GMainLoop *loop_ = nullptr;
    std::thread thread_;
    GstElement *pipeline_ = nullptr;
    GstElement *appsrc_ = nullptr; // in pipeline_ (no reference of its own)
    GstElement *encoder_ = nullptr;
    GstAllocator *dmabufAllocator_ = nullptr; // zero copy: wraps the capture buffers' DMABUF (EngineFormat::dmabuf)
    GSource *busWatch_ = nullptr;
    std::vector<std::unique_ptr<RtspOutput>> rtsp_;
    std::vector<std::unique_ptr<EncodedOutput>> outputs_; // recordings and pushes
    std::unique_ptr<WebrtcPeers> webrtc_;                 // [webrtc] enabled: for as long as the engine
    std::optional<std::chrono::nanoseconds> firstCapture_;
    GstClockTime nextKeyframe_ = 0; // PTS: the first frame at or past it is forced to be a keyframe

    mutable std::mutex mutex_;
    EngineState state_;
    std::deque<std::pair<GstClockTime, size_t>> lastSecond_; // (arrival, bytes) of the last second's access units
    LatencyHistogram encoderIn_, encoded_, sent_, webrtcSent_;
    std::deque<std::pair<GstClockTime, GstClockTime>> blendedAt_; // (PTS, blended) of the frames pushed last
};

} // namespace overlayd
