// SPDX-License-Identifier: Apache-2.0
// RecordOutput: format-location runs on splitmuxsink's streaming thread, the bus and the timer on the engine's main
// loop; the mutex guards the directory's bookkeeping they share.
#include "stream/gst/record_output.h"

#include <algorithm>

#include <gst/app/gstappsrc.h>

#include <cstdio>

namespace overlayd {
namespace {

RetentionLimits limitsOf(const RecordSinkOptions &options)
{
    return {options.keepBytes, std::chrono::seconds(int64_t(options.keepDays * 86400))};
}

std::string baseName(const std::string &path)
{
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

} // namespace

RecordOutput::RecordOutput(const EncodedSinkOptions &options, double keyframeIntervalSec, const EngineLog &log,
                           std::function<void()> requestKeyframe)
    : options_(options), keyframeIntervalSec_(keyframeIntervalSec), log_(log), feed_(std::move(requestKeyframe)),
      store_(options.record.directory), directory_(store_, options.record.container, limitsOf(options.record))
{}

RecordOutput::~RecordOutput()
{
    // The engine's loop has stopped: the end of the last segment is waited for here, on this thread.
    feed_.endOfStream();
    if (branch_.pipeline != nullptr) {
        GstBus *bus = gst_element_get_bus(branch_.pipeline);
        const auto types = GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_ELEMENT);
        while (GstMessage *message = gst_bus_timed_pop_filtered(bus, 3 * GST_SECOND, types)) {
            const bool last = GST_MESSAGE_TYPE(message) != GST_MESSAGE_ELEMENT;
            handle(message);
            gst_message_unref(message);
            if (last)
                break;
        }
        gst_object_unref(bus);
    }
    teardown();
    dropSource(timer_);
}

Status RecordOutput::start(GMainContext *context)
{
    context_ = context;
    {
        std::lock_guard lock(mutex_);
        // What a crash left is finished first, so that the first new segment's name never meets it.
        if (auto recovered = directory_.recover(WallClock::now()); !recovered)
            log_(kLogWarning, options_.key + ": " + recovered.error().message);
        if (directory_.figures().recovered > 0)
            log_(kLogNotice, options_.key + ": " + std::to_string(directory_.figures().recovered) +
                                 " segment(s) left partial by a crash kept, readable up to their last fragment");
    }
    if (auto writable = store_.checkWritable(); !writable)
        return makeError(writable.error().code, options_.key + ".directory: " + writable.error().message);
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%g", options_.record.segmentSec);
    log_(kLogInfo, options_.key + ": recording to " + store_.directory() + " in " + seconds + " s segments");
    return build();
}

Status RecordOutput::build()
{
    branch_.pipeline = gst_pipeline_new(nullptr);
    GstElement *appsrc = gst_element_factory_make("appsrc", nullptr);
    GstElement *parse = gst_element_factory_make("h264parse", nullptr);
    GstElement *mux = gst_element_factory_make("splitmuxsink", nullptr);
    if (!appsrc || !parse || !mux) {
        for (GstElement *element : {appsrc, parse, mux})
            if (element)
                gst_object_unref(gst_object_ref_sink(element));
        gst_object_unref(branch_.pipeline), branch_.pipeline = nullptr;
        return makeError(ErrorCode::NotFound, options_.key + ": GStreamer's splitmuxsink or h264parse is missing "
                                                             "(Debian: gstreamer1.0-plugins-good, -bad)");
    }
    g_object_set(appsrc, "is-live", TRUE, "format", GST_FORMAT_TIME, "block", FALSE, nullptr);
    const bool mp4 = options_.record.container == RecordContainer::Mp4;
    // async-finalize: a segment's muxer finishes in the background while the next one starts; it is also the
    // only way to give the muxer properties (the fragments that make a killed MP4 readable).
    // splitmuxsink cuts before a keyframe interval that would pass max-size-time by any amount, and keyframes land
    // up to a frame period after their grid points: without the slack, segment_s = 2 with keyframes every second cut
    // 1 s files, and every 0.5 s at 15 fps 1.6 s files.
    const guint64 slack = std::max(kMinSegmentSlackNs, guint64(keyframeIntervalSec_ / 2 * GST_SECOND));
    const guint64 maxTime = guint64(options_.record.segmentSec * GST_SECOND) + slack;
    g_object_set(mux, "max-size-time", maxTime, "async-finalize", TRUE, "muxer-factory", mp4 ? "mp4mux" : "matroskamux",
                 nullptr);
    if (mp4) {
        GstStructure *properties =
            gst_structure_new("properties", "fragment-duration", G_TYPE_UINT, kFragmentMs, nullptr);
        g_object_set(mux, "muxer-properties", properties, nullptr);
        gst_structure_free(properties);
    }
    // Unbuffered: each fragment reaches the kernel as the muxer writes it, so a SIGKILL loses nothing written
    // (filesink's default 64 KiB buffer held whole segments of a quiet scene).
    GType bufferMode = g_type_from_name("GstFileSinkBufferMode");
    if (bufferMode == 0) { // registered with filesink's class, on its first use
        gst_object_unref(gst_object_ref_sink(gst_element_factory_make("filesink", nullptr)));
        bufferMode = g_type_from_name("GstFileSinkBufferMode");
    }
    GstStructure *sinkProperties = gst_structure_new("properties", "buffer-mode", bufferMode, 2, nullptr);
    g_object_set(mux, "sink-properties", sinkProperties, nullptr);
    gst_structure_free(sinkProperties);
    g_signal_connect(mux, "format-location", G_CALLBACK(&RecordOutput::onFormatLocation), this);
    gst_bin_add_many(GST_BIN(branch_.pipeline), appsrc, parse, mux, nullptr);
    if (!gst_element_link_many(appsrc, parse, mux, nullptr)) {
        teardown();
        return makeError(ErrorCode::Unsupported, options_.key + ": h264parse does not link to splitmuxsink");
    }
    branch_.watch(context_, &RecordOutput::onBusMessage, this);
    if (gst_element_set_state(branch_.pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
        teardown();
        return makeError(ErrorCode::Io, options_.key + ": the recording pipeline does not start");
    }
    feed_.attach(appsrc);
    return Ok{};
}

void RecordOutput::teardown()
{
    feed_.detach();
    branch_.drop();
    std::lock_guard lock(mutex_);
    current_.clear();
    if (auto recovered = directory_.recover(WallClock::now()); !recovered)
        log_(kLogWarning, options_.key + ": " + recovered.error().message);
}

gchar *RecordOutput::onFormatLocation(GstElement *, guint, gpointer data)
{
    auto *self = static_cast<RecordOutput *>(data);
    std::lock_guard lock(self->mutex_);
    const std::string partial = self->directory_.nextPartialName(WallClock::now());
    self->current_ = partial.substr(0, partial.size() - kPartialSuffix.size());
    return g_strdup((self->store_.directory() + "/" + partial).c_str());
}

gboolean RecordOutput::onBusMessage(GstBus *, GstMessage *message, gpointer data)
{
    static_cast<RecordOutput *>(data)->handle(message);
    return G_SOURCE_CONTINUE;
}

void RecordOutput::handle(GstMessage *message)
{
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ELEMENT) {
        const GstStructure *structure = gst_message_get_structure(message);
        if (!gst_structure_has_name(structure, "splitmuxsink-fragment-closed"))
            return;
        const gchar *location = gst_structure_get_string(structure, "location");
        if (location == nullptr)
            return;
        std::lock_guard lock(mutex_);
        if (auto finished = directory_.finish(baseName(location), WallClock::now()); !finished)
            log_(kLogWarning, options_.key + ": " + finished.error().message);
        else
            retry_.reset(); // a whole segment written: the next failure starts its back-off afresh
    } else if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
        GError *error = nullptr;
        gst_message_parse_error(message, &error, nullptr);
        onError(error);
        g_clear_error(&error);
    }
}

void RecordOutput::onError(GError *error)
{
    const std::string reason = error ? error->message : "?";
    const bool noSpace =
        error && error->domain == GST_RESOURCE_ERROR && error->code == GST_RESOURCE_ERROR_NO_SPACE_LEFT;
    if (branch_.pipeline == nullptr)
        return; // the rest of a failure already handled
    teardown();
    std::unique_lock lock(mutex_);
    lastError_ = reason;
    if (noSpace) {
        if (gate_.noSpace())
            log_(kLogError, options_.key + ": " + store_.directory() +
                                " is full: recording stopped (the stream goes on) until " +
                                std::to_string(DiskSpaceGate::resumeBytes(directory_.largestSegmentBytes()) >> 20) +
                                " MiB are free");
        lock.unlock();
        replaceTimer(timer_, context_, kSpaceCheckMs, &RecordOutput::onTimer, this);
        return;
    }
    lock.unlock();
    const auto delay = retry_.next();
    log_(kLogWarning,
         options_.key + ": recording failed (" + reason + "): retrying in " + std::to_string(delay.count()) + " ms");
    replaceTimer(timer_, context_, guint(delay.count()), &RecordOutput::onTimer, this);
}

gboolean RecordOutput::onTimer(gpointer data)
{
    auto *self = static_cast<RecordOutput *>(data);
    {
        std::lock_guard lock(self->mutex_);
        if (self->gate_.stopped()) {
            const auto free = self->store_.freeBytes();
            if (!free || !self->gate_.spaceReturned(*free, self->directory_.largestSegmentBytes()))
                return G_SOURCE_CONTINUE; // looked at again in kSpaceCheckMs
            self->log_(kLogNotice,
                       self->options_.key + ": space is back in " + self->store_.directory() + ": recording again");
        }
    }
    g_source_unref(self->timer_); // the loop holds its own reference until this returns REMOVE
    self->timer_ = nullptr;
    if (auto built = self->build(); !built) {
        const auto delay = self->retry_.next();
        self->log_(kLogWarning, built.error().message + ": retrying in " + std::to_string(delay.count()) + " ms");
        replaceTimer(self->timer_, self->context_, guint(delay.count()), &RecordOutput::onTimer, self);
    }
    return G_SOURCE_REMOVE;
}

EncodedSinkState RecordOutput::state() const
{
    EncodedSinkState out;
    out.kind = "record";
    out.key = options_.key;
    out.describe = store_.directory();
    out.dropped = feed_.dropped();
    std::lock_guard lock(mutex_);
    const RecordFigures &figures = directory_.figures();
    out.currentFile = current_;
    out.segments = figures.segments;
    out.bytes = figures.bytes;
    out.oldest = figures.oldest;
    out.deleted = figures.deleted;
    out.diskFull = gate_.stopped();
    out.diskFullStops = gate_.stops();
    out.lastError = lastError_;
    return out;
}

} // namespace overlayd
