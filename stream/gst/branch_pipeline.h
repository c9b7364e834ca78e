// SPDX-License-Identifier: Apache-2.0
// BranchPipeline: the pipeline of a recording or a push with its bus watch on the engine's main context, dropped
// together; and the one retry/check timer each keeps on that context.
#pragma once

#include <gst/gst.h>

namespace overlayd {

struct BranchPipeline {
    GstElement *pipeline = nullptr;
    GSource *busWatch = nullptr;

    // The bus's messages go to `callback` on `context`'s loop.
    void watch(GMainContext *context, GstBusFunc callback, gpointer data);
    // Stopped (NULL: every buffer and file handle let go) and released; safe when there is none.
    void drop();
};

// `timer` replaced by one that calls `callback` every `delayMs` on `context` (until it returns G_SOURCE_REMOVE).
void replaceTimer(GSource *&timer, GMainContext *context, guint delayMs, GSourceFunc callback, gpointer data);
void dropSource(GSource *&source);

} // namespace overlayd
