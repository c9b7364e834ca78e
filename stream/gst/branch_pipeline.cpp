// SPDX-License-Identifier: Apache-2.0
// BranchPipeline: destroying a source that is dispatching is allowed; the loop keeps its own reference until the
// callback returns.
#include "stream/gst/branch_pipeline.h"

namespace overlayd {

void BranchPipeline::watch(GMainContext *context, GstBusFunc callback, gpointer data)
{
    GstBus *bus = gst_element_get_bus(pipeline);
    busWatch = gst_bus_create_watch(bus);
    g_source_set_callback(busWatch, G_SOURCE_FUNC(callback), data, nullptr);
    g_source_attach(busWatch, context);
    gst_object_unref(bus);
}

void BranchPipeline::drop()
{
    dropSource(busWatch);
    if (pipeline != nullptr) {
        gst_element_set_state(pipeline, GST_STATE_NULL);
        gst_object_unref(pipeline);
        pipeline = nullptr;
    }
}

void replaceTimer(GSource *&timer, GMainContext *context, guint delayMs, GSourceFunc callback, gpointer data)
{
    dropSource(timer);
    timer = g_timeout_source_new(delayMs);
    g_source_set_callback(timer, callback, data, nullptr);
    g_source_attach(timer, context);
}

void dropSource(GSource *&source)
{
    if (source == nullptr)
        return;
    g_source_destroy(source);
    g_source_unref(source);
    source = nullptr;
}

} // namespace overlayd
