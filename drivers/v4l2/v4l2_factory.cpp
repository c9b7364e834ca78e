// SPDX-License-Identifier: Apache-2.0
// The V4L2 entry points: the capture source and the output sink on the real kernel.
#include "drivers/v4l2/v4l2_factory.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "drivers/v4l2/capture_source.h"
#include "drivers/v4l2/output_sink.h"
#include "drivers/v4l2/v4l2_syscalls.h"

namespace overlayd {

namespace {

// Until the daemon hands its logger down, the few driver lines go to stderr, with journald's "notice" priority
// prefix when stderr is the journal (systemd sets JOURNAL_STREAM for the service).
void logToStderr(const std::string &line)
{
    std::fprintf(stderr, "%sv4l2: %s\n", std::getenv("JOURNAL_STREAM") ? "<5>" : "", line.c_str());
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeV4l2Source(const SourceOptions &options)
{
    return makeV4l2Source(options, logToStderr);
}

Result<std::unique_ptr<FrameSource>> makeV4l2Source(const SourceOptions &options,
                                                    std::function<void(const std::string &)> log)
{
    if (options.v4l2.bufferCount < 2 || options.v4l2.bufferCount > 32)
        return makeError(ErrorCode::ConfigError,
                         "source.v4l2.buffers must be 2..32 (got " + std::to_string(options.v4l2.bufferCount) + ")");
    return std::unique_ptr<FrameSource>(std::make_unique<V4l2CaptureSource>(realSyscalls(), options, std::move(log)));
}

Result<std::unique_ptr<FrameSink>> makeV4l2OutputSink(const SinkOptions &options)
{
    if (options.bufferCount < 2 || options.bufferCount > 32)
        return makeError(ErrorCode::ConfigError,
                         "sink buffers must be 2..32 (got " + std::to_string(options.bufferCount) + ")");
    if (options.path.empty())
        return makeError(ErrorCode::ConfigError, "a v4l2 sink needs a device path");
    return std::unique_ptr<FrameSink>(std::make_unique<V4l2OutputSink>(realSyscalls(), options, logToStderr));
}

} // namespace overlayd
