// SPDX-License-Identifier: Apache-2.0
// The V4L2 entry points the driver factory calls (drivers/v4l2/ implements them).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "base/result.h"
#include "drivers/frame_sink.h"
#include "drivers/frame_source.h"
#include "drivers/sink_options.h"
#include "drivers/source_options.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> makeV4l2Source(const SourceOptions &options);
// The same, with the source's few log lines (the negotiation adjustment) going to `log` instead of stderr.
Result<std::unique_ptr<FrameSource>> makeV4l2Source(const SourceOptions &options,
                                                    std::function<void(const std::string &)> log);
Result<std::unique_ptr<FrameSink>> makeV4l2OutputSink(const SinkOptions &options);

} // namespace overlayd
