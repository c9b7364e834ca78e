// SPDX-License-Identifier: Apache-2.0
// RecordOutput: one kind = "record" sink. Its own pipeline, fed through a BranchFeed:
//
//   appsrc ! h264parse ! splitmuxsink (mp4mux with 1 s fragments, or matroskamux; a new file every segment_s)
//
// Each segment is written as "<UTC start>.mp4.partial" (splitmuxsink's format-location) and renamed when
// splitmuxsink reports it closed; retention runs after each. A full disk stops the pipeline (the stream and the
// other sinks go on) and a timer on the main loop starts it again when a segment fits; any other failure is
// retried with back-off.
#pragma once

#include <gst/gst.h>

#include <functional>
#include <mutex>
#include <string>

#include "base/backoff.h"
#include "stream/directory_segment_store.h"
#include "stream/disk_space_gate.h"
#include "stream/gst/branch_feed.h"
#include "stream/gst/branch_pipeline.h"
#include "stream/gst/encoded_output.h"
#include "stream/record_directory.h"

namespace overlayd {

// Fragments of a recording's MP4 files: what a power cut loses at most, after the picture group splitmuxsink holds.
inline constexpr guint kFragmentMs = 1000;
// Added to segment_s for splitmuxsink (record_output.cpp), at least: splitmuxsink cuts before a picture group that
// would pass its limit by any amount. The engine places keyframes on a grid of keyframe_s from the first frame, each
// on the first frame at or past its grid point, so a picture group ends up to a frame period late; the slack is half
// a keyframe interval, and never less than this (a loaded machine's timestamp jitter).
inline constexpr guint64 kMinSegmentSlackNs = 100 * GST_MSECOND;
// While stopped for space, the free space is looked at this often.
inline constexpr guint kSpaceCheckMs = 1000;

class RecordOutput : public EncodedOutput
{
public:
    // keyframeIntervalSec: the encoder's keyframe_s, by which the segments' cuts are placed.
    RecordOutput(const EncodedSinkOptions &options, double keyframeIntervalSec, const EngineLog &log,
                 std::function<void()> requestKeyframe);
    ~RecordOutput() override;

    Status start(GMainContext *context) override;
    void push(GstSample *sample) override { feed_.push(sample); }
    EncodedSinkState state() const override;

private:
    Status build();
    // The pipeline set to NULL and dropped; its partial segment (readable up to its last fragment) is finished.
    void teardown();
    void onError(GError *error);
    static gchar *onFormatLocation(GstElement *, guint, gpointer self);
    static gboolean onBusMessage(GstBus *, GstMessage *message, gpointer self);
    static gboolean onTimer(gpointer self);
    void handle(GstMessage *message);

    EncodedSinkOptions options_;
    double keyframeIntervalSec_;
    EngineLog log_;
    BranchFeed feed_;
    DirectorySegmentStore store_;
    GMainContext *context_ = nullptr;
    BranchPipeline branch_;
    GSource *timer_ = nullptr;
    Backoff retry_{Backoff::Duration(1000), Backoff::Duration(16000)};

    mutable std::mutex mutex_; // the directory and the figures: format-location runs on a streaming thread
    RecordDirectory directory_;
    DiskSpaceGate gate_;
    std::string current_; // the segment being written (its final name)
    std::string lastError_;
};

} // namespace overlayd
