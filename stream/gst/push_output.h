// SPDX-License-Identifier: Apache-2.0
// PushOutput: one kind = "push" sink. Its own pipeline, fed through a BranchFeed:
//
//   appsrc ! h264parse config-interval=-1 ! rtspclientsink (TCP)       rtsp://: ANNOUNCE, then RECORD
//                                         ! flvmux ! rtmp2sink         rtmp://: publish
//                                         ! mpegtsmux ! srtsink        srt://:  caller
//
// A server that is down or goes away tears the pipeline down and a timer on the engine's loop builds it again after
// a back-off (PushLink); nothing of this runs on the encoder's thread, so the stream and the other sinks never wait.
// Connected means the pipeline plays and access units leave it.
#pragma once

#include <gst/gst.h>

#include <atomic>
#include <functional>
#include <mutex>

#include "stream/gst/branch_feed.h"
#include "stream/gst/branch_pipeline.h"
#include "stream/gst/encoded_output.h"
#include "stream/push_link.h"

namespace overlayd {

// How often a push looks whether its access units flow (connected) while it runs.
inline constexpr guint kPushCheckMs = 500;

class PushOutput : public EncodedOutput
{
public:
    PushOutput(const EncodedSinkOptions &options, const EngineLog &log, std::function<void()> requestKeyframe);
    ~PushOutput() override;

    Status start(GMainContext *context) override;
    void push(GstSample *sample) override { feed_.push(sample); }
    EncodedSinkState state() const override;

private:
    Status build();
    void teardown();
    void failed(const std::string &reason);
    static gboolean onBusMessage(GstBus *, GstMessage *message, gpointer self);
    static gboolean onRetry(gpointer self);
    static gboolean onCheck(gpointer self);
    static GstPadProbeReturn onBuffer(GstPad *, GstPadProbeInfo *, gpointer self);

    EncodedSinkOptions options_;
    EngineLog log_;
    BranchFeed feed_;
    GMainContext *context_ = nullptr;
    BranchPipeline branch_;
    GSource *timer_ = nullptr;
    std::atomic<uint64_t> sent_{0}; // access units out of h264parse towards the server
    uint64_t sentAtCheck_ = 0;

    mutable std::mutex mutex_;
    PushLink link_;
};

} // namespace overlayd
