// SPDX-License-Identifier: Apache-2.0
// The file sinks: Y4M, raw frames, PNG/JPEG snapshots and the null sink.
#pragma once

#include <memory>

#include "base/result.h"
#include "drivers/sink_options.h"

namespace overlayd {

// Each checks its options (path, extension, every, quality) and opens nothing until FrameSink::open.
Result<std::unique_ptr<FrameSink>> makeY4mSink(const SinkOptions &options);
Result<std::unique_ptr<FrameSink>> makeRawSink(const SinkOptions &options);
Result<std::unique_ptr<FrameSink>> makeSnapshotSink(const SinkOptions &options);
Result<std::unique_ptr<FrameSink>> makeNullSink(const SinkOptions &options);

// The Y4M colour space a format is written as: "420jpeg" (YUV420, YVU420, NV12, NV21), "422" (YUYV, UYVY, YVYU,
// NV16), "mono" (GREY), "444" (RGB formats, encoded in the stream's colorimetry).
const char *y4mChromaTagFor(const PixelFormatInfo &format);

} // namespace overlayd
