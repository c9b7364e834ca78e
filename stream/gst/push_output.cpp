// SPDX-License-Identifier: Apache-2.0
// PushOutput: the bus, the retry and the check timers run on the engine's main loop; the buffer probe on the
// streaming thread only counts.
#include "stream/gst/push_output.h"

namespace overlayd {
namespace {

// The elements after h264parse for each protocol, the last one taking the URL in `property`.
struct Route {
    const char *muxer; // null: the sink takes H.264 itself
    const char *sink;
    const char *property;
};

Route routeOf(PushProtocol protocol)
{
    switch (protocol) {
    case PushProtocol::Rtmp:
        return {"flvmux", "rtmp2sink", "location"};
    case PushProtocol::Srt:
        return {"mpegtsmux", "srtsink", "uri"};
    case PushProtocol::Rtsp:
        break;
    }
    return {nullptr, "rtspclientsink", "location"};
}

} // namespace

PushOutput::PushOutput(const EncodedSinkOptions &options, const EngineLog &log, std::function<void()> requestKeyframe)
    : options_(options), log_(log), feed_(std::move(requestKeyframe))
{}

PushOutput::~PushOutput()
{
    teardown();
    dropSource(timer_);
}

Status PushOutput::start(GMainContext *context)
{
    context_ = context;
    log_(kLogNotice, options_.key + ": pushing to " + options_.push.url + " when it answers");
    if (auto built = build(); !built)
        return built;
    if (branch_.pipeline != nullptr) // else a retry is scheduled already
        replaceTimer(timer_, context_, kPushCheckMs, &PushOutput::onCheck, this);
    return Ok{};
}

Status PushOutput::build()
{
    const Route route = routeOf(options_.push.protocol);
    branch_.pipeline = gst_pipeline_new(nullptr);
    GstElement *appsrc = gst_element_factory_make("appsrc", nullptr);
    GstElement *parse = gst_element_factory_make("h264parse", nullptr);
    GstElement *muxer = route.muxer ? gst_element_factory_make(route.muxer, nullptr) : nullptr;
    GstElement *sink = gst_element_factory_make(route.sink, nullptr);
    if (!appsrc || !parse || !sink || (route.muxer && !muxer)) {
        for (GstElement *element : {appsrc, parse, muxer, sink})
            if (element)
                gst_object_unref(gst_object_ref_sink(element));
        gst_object_unref(branch_.pipeline), branch_.pipeline = nullptr;
        return makeError(ErrorCode::NotFound, options_.key + ": GStreamer's " + route.sink +
                                                  (route.muxer ? std::string(" or ") + route.muxer : "") +
                                                  " is missing (Debian: gstreamer1.0-plugins-bad, gstreamer1.0-rtsp)");
    }
    g_object_set(appsrc, "is-live", TRUE, "format", GST_FORMAT_TIME, "block", FALSE, nullptr);
    // Parameter sets before every keyframe: a server (or its viewers) may start at any of them.
    g_object_set(parse, "config-interval", -1, nullptr);
    g_object_set(sink, route.property, options_.push.url.c_str(), nullptr);
    if (options_.push.protocol == PushProtocol::Rtsp)
        gst_util_set_object_arg(G_OBJECT(sink), "protocols", "tcp"); // through NAT and firewalls, as servers expect
    if (options_.push.protocol == PushProtocol::Rtmp)
        g_object_set(muxer, "streamable", TRUE, nullptr);
    if (options_.push.protocol == PushProtocol::Srt)
        g_object_set(muxer, "alignment", 7, nullptr); // 7 TS packets per datagram: what SRT receivers expect
    gst_bin_add_many(GST_BIN(branch_.pipeline), appsrc, parse, sink, nullptr);
    if (muxer)
        gst_bin_add(GST_BIN(branch_.pipeline), muxer);
    const bool linked = muxer ? gst_element_link_many(appsrc, parse, muxer, sink, nullptr)
                              : gst_element_link_many(appsrc, parse, sink, nullptr);
    if (!linked) {
        teardown();
        return makeError(ErrorCode::Unsupported, options_.key + ": h264parse does not link to " + route.sink);
    }
    GstPad *out = gst_element_get_static_pad(parse, "src");
    gst_pad_add_probe(out, GST_PAD_PROBE_TYPE_BUFFER, &PushOutput::onBuffer, this, nullptr);
    gst_object_unref(out);
    branch_.watch(context_, &PushOutput::onBusMessage, this);
    feed_.attach(appsrc);
    // A server that is down fails here (rtspclientsink connects while it starts) or on the bus: both are retried.
    if (gst_element_set_state(branch_.pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE)
        failed("the server does not answer");
    return Ok{};
}

void PushOutput::teardown()
{
    feed_.detach();
    branch_.drop();
}

void PushOutput::failed(const std::string &reason)
{
    if (branch_.pipeline == nullptr)
        return; // the rest of a failure already handled
    teardown();
    PushLink::Retry retry;
    {
        std::lock_guard lock(mutex_);
        retry = link_.failed(reason);
    }
    if (retry.newReason)
        log_(kLogWarning, options_.key + ": push to " + options_.push.url + " failed (" + reason +
                              "): retrying with back-off, from " + std::to_string(retry.delay.count()) + " ms");
    replaceTimer(timer_, context_, guint(retry.delay.count()), &PushOutput::onRetry, this);
}

gboolean PushOutput::onRetry(gpointer data)
{
    auto *self = static_cast<PushOutput *>(data);
    {
        std::lock_guard lock(self->mutex_);
        self->link_.retrying();
    }
    self->sentAtCheck_ = self->sent_.load();
    if (auto built = self->build(); !built)
        self->log_(kLogWarning, built.error().message);
    if (self->branch_.pipeline != nullptr) // else failed() has scheduled the next attempt
        replaceTimer(self->timer_, self->context_, kPushCheckMs, &PushOutput::onCheck, self);
    return G_SOURCE_CONTINUE; // replaceTimer() has destroyed this source when it ran
}

gboolean PushOutput::onCheck(gpointer data)
{
    auto *self = static_cast<PushOutput *>(data);
    const uint64_t sent = self->sent_.load();
    const bool flowing = sent > self->sentAtCheck_;
    self->sentAtCheck_ = sent;
    GstState state = GST_STATE_NULL;
    if (self->branch_.pipeline != nullptr)
        gst_element_get_state(self->branch_.pipeline, &state, nullptr, 0);
    std::lock_guard lock(self->mutex_);
    if (flowing && state == GST_STATE_PLAYING && !self->link_.isConnected()) {
        self->link_.connected();
        self->log_(kLogNotice, self->options_.key + ": pushing to " + self->options_.push.url);
    }
    return G_SOURCE_CONTINUE;
}

GstPadProbeReturn PushOutput::onBuffer(GstPad *, GstPadProbeInfo *, gpointer data)
{
    ++static_cast<PushOutput *>(data)->sent_;
    return GST_PAD_PROBE_OK;
}

gboolean PushOutput::onBusMessage(GstBus *, GstMessage *message, gpointer data)
{
    auto *self = static_cast<PushOutput *>(data);
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
        GError *error = nullptr;
        gst_message_parse_error(message, &error, nullptr);
        const std::string reason = error ? error->message : "?";
        g_clear_error(&error);
        self->failed(reason); // destroys this watch: its callback is not called again
    }
    return G_SOURCE_CONTINUE;
}

EncodedSinkState PushOutput::state() const
{
    EncodedSinkState out;
    out.kind = "push";
    out.key = options_.key;
    out.describe = options_.push.url;
    out.dropped = feed_.dropped();
    std::lock_guard lock(mutex_);
    out.connected = link_.isConnected();
    out.reconnects = link_.reconnects();
    out.lastError = link_.lastError();
    return out;
}

} // namespace overlayd
