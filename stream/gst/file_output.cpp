// SPDX-License-Identifier: Apache-2.0
// FileOutput: the bus runs on the engine's main loop; push() on the encoder's streaming thread goes through the
// BranchFeed, which starts the file at a keyframe.
#include "stream/gst/file_output.h"

namespace overlayd {
FileOutput::FileOutput(const EncodedSinkOptions &options, Codec codec, const EngineLog &log,
                       std::function<void()> requestKeyframe)
    : options_(options), log_(log), feed_(std::move(requestKeyframe), codec == Codec::Fwht)
{}

FileOutput::~FileOutput()
{
    // The engine's loop has stopped: the end of stream reaches filesink here, so that the file is complete.
    feed_.endOfStream();
    if (branch_.pipeline != nullptr) {
        GstBus *bus = gst_element_get_bus(branch_.pipeline);
        if (GstMessage *message =
                gst_bus_timed_pop_filtered(bus, 3 * GST_SECOND, GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR)))
            gst_message_unref(message);
        gst_object_unref(bus);
    }
    feed_.detach();
    branch_.drop();
}

Status FileOutput::start(GMainContext *context)
{
    branch_.pipeline = gst_pipeline_new(nullptr);
    GstElement *appsrc = gst_element_factory_make("appsrc", nullptr);
    GstElement *sink = gst_element_factory_make("filesink", nullptr);
    if (!appsrc || !sink) {
        for (GstElement *element : {appsrc, sink})
            if (element)
                gst_object_unref(gst_object_ref_sink(element));
        gst_object_unref(branch_.pipeline), branch_.pipeline = nullptr;
        return makeError(ErrorCode::NotFound, options_.key + ": GStreamer's appsrc or filesink is missing "
                                                             "(Debian: gstreamer1.0-plugins-base)");
    }
    g_object_set(appsrc, "is-live", TRUE, "format", GST_FORMAT_TIME, "block", FALSE, nullptr);
    g_object_set(sink, "location", options_.file.path.c_str(), "sync", FALSE, nullptr);
    gst_bin_add_many(GST_BIN(branch_.pipeline), appsrc, sink, nullptr);
    gst_element_link(appsrc, sink);
    branch_.watch(context, &FileOutput::onBusMessage, this);
    if (gst_element_set_state(branch_.pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
        branch_.drop();
        return makeError(ErrorCode::Io, options_.key + ".path: '" + options_.file.path + "' cannot be written");
    }
    feed_.attach(appsrc);
    return Ok{};
}

gboolean FileOutput::onBusMessage(GstBus *, GstMessage *message, gpointer data)
{
    auto *self = static_cast<FileOutput *>(data);
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
        GError *error = nullptr;
        gst_message_parse_error(message, &error, nullptr);
        const std::string text = error ? error->message : "?";
        g_clear_error(&error);
        self->log_(kLogError, self->options_.key + ": " + text + " (the file sink stops)");
        std::lock_guard lock(self->mutex_);
        self->lastError_ = text;
        self->feed_.detach();
    }
    return G_SOURCE_CONTINUE;
}

EncodedSinkState FileOutput::state() const
{
    EncodedSinkState out;
    out.kind = "file";
    out.key = options_.key;
    out.describe = options_.file.path;
    out.currentFile = options_.file.path;
    out.dropped = feed_.dropped();
    std::lock_guard lock(mutex_);
    out.lastError = lastError_;
    return out;
}

} // namespace overlayd
