// SPDX-License-Identifier: Apache-2.0
// FileOutput: one kind = "file" sink. The encoder's elementary stream, unmuxed, into one file through a pipeline of
// its own fed by a BranchFeed: appsrc -> filesink. It is how vicodec's FWHT frames (which no muxer takes) leave the
// daemon, to be decoded back by vicodec's decoder; an H.264 byte stream goes the same way.
#pragma once

#include <functional>
#include <mutex>

#include "stream/gst/branch_feed.h"
#include "stream/gst/branch_pipeline.h"
#include "stream/gst/encoded_output.h"
#include "stream/stream_options.h"

namespace overlayd {

class FileOutput : public EncodedOutput
{
public:
    FileOutput(const EncodedSinkOptions &options, Codec codec, const EngineLog &log,
               std::function<void()> requestKeyframe);
    ~FileOutput() override;
    FileOutput(const FileOutput &) = delete;
    FileOutput &operator=(const FileOutput &) = delete;

    Status start(GMainContext *context) override;
    void push(GstSample *sample) override { feed_.push(sample); }
    EncodedSinkState state() const override;

private:
    static gboolean onBusMessage(GstBus *bus, GstMessage *message, gpointer data);

    EncodedSinkOptions options_;
    const EngineLog &log_;
    BranchFeed feed_;
    BranchPipeline branch_;
    mutable std::mutex mutex_; // lastError_: written on the engine's loop, read by whoever asks for the state
    std::string lastError_;
};

} // namespace overlayd
