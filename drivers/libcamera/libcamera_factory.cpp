// SPDX-License-Identifier: Apache-2.0
// The libcamera entry points the driver factory calls, in builds with libcamera.
#include "drivers/libcamera/libcamera_factory.h"

#include <cstdio>
#include <cstdlib>

#include "drivers/libcamera/libcamera_source.h"

namespace overlayd {

bool libcameraBuiltIn()
{
    return true;
}

Result<std::unique_ptr<FrameSource>> makeLibcameraSource(const SourceOptions &options)
{
    if (options.libcamera.bufferCount < 2 || options.libcamera.bufferCount > 32)
        return makeError(ErrorCode::ConfigError, "source.libcamera.buffers must be 2..32 (got " +
                                                     std::to_string(options.libcamera.bufferCount) + ")");
    return std::unique_ptr<FrameSource>(std::make_unique<LibcameraSource>(options, [](const std::string &line) {
        std::fprintf(stderr, "%slibcamera: %s\n", std::getenv("JOURNAL_STREAM") ? "<5>" : "", line.c_str());
    }));
}

} // namespace overlayd
