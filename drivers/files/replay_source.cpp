// SPDX-License-Identifier: Apache-2.0
// makeReplaySource: resolves ReplayFormat::Auto from the path and hands over to the format's source.
#include "drivers/files/replay_source.h"

#include "drivers/files/path_pattern.h"
#include "drivers/files/replay_base.h"

namespace overlayd {

namespace {

ReplayFormat resolve(const ReplayOptions &replay)
{
    if (replay.format != ReplayFormat::Auto)
        return replay.format;
    const std::string extension = lowerExtension(replay.path);
    if (extension == ".y4m")
        return ReplayFormat::Y4m;
    if (hasIndexPattern(replay.path) || extension == ".png" || extension == ".jpg" || extension == ".jpeg")
        return ReplayFormat::Images;
    return ReplayFormat::Raw;
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeReplaySource(const SourceOptions &options)
{
    if (options.replay.path.empty())
        return makeError(ErrorCode::InvalidArgument, "replay needs a path");
    switch (resolve(options.replay)) {
    case ReplayFormat::Y4m:
        return makeY4mSource(options);
    case ReplayFormat::Images:
        return makeImageSource(options);
    default:
        return makeRawSource(options);
    }
}

} // namespace overlayd
