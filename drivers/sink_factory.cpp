// SPDX-License-Identifier: Apache-2.0
// makeSink: the one place that maps a configured sink kind to its implementation.
#include "drivers/sink_options.h"

#include <filesystem>

#include "drivers/files/file_sinks.h"
#include "drivers/files/path_pattern.h"
#include "drivers/v4l2/v4l2_factory.h"

namespace overlayd {

namespace {

// The kind of what is at `path` now, when it cannot take a sink's frames; empty when it can (or is not there yet:
// the sink creates it, and its folders).
std::string unwritableKind(const std::filesystem::path &path)
{
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (std::filesystem::is_directory(status))
        return "a directory";
    if (std::filesystem::is_block_file(status))
        return "a block device";
    if (std::filesystem::is_socket(status))
        return "a socket";
    for (std::filesystem::path folder = path.parent_path(); !folder.empty(); folder = folder.parent_path()) {
        const auto kind = std::filesystem::status(folder, error);
        if (std::filesystem::exists(kind))
            return std::filesystem::is_directory(kind) ? "" : "in '" + folder.string() + "', which is not a folder";
        if (folder == folder.parent_path())
            break;
    }
    return "";
}

std::optional<SinkProblem> checkFilePath(const SinkOptions &options)
{
    if (options.path.empty())
        return SinkProblem{"path", "must not be empty"};
    std::string path = options.path;
    if (options.kind == SinkKind::Snapshot) {
        const std::string extension = lowerExtension(options.path);
        if (extension != ".png" && extension != ".jpg" && extension != ".jpeg")
            return SinkProblem{"path", "a snapshot path must end in .png, .jpg or .jpeg"};
        auto first = formatIndex(options.path, 0);
        if (!first)
            return SinkProblem{"path", first.error().message};
        path = *first;
    }
    if (path == "-" && options.kind == SinkKind::Y4m)
        return std::nullopt;
    if (const std::string kind = unwritableKind(path); !kind.empty())
        return SinkProblem{"path", "'" + path + "' is " + kind + ": a " +
                                       (options.kind == SinkKind::Snapshot ? "snapshot" : "file") +
                                       " sink writes a file, a FIFO or a character device"};
    return std::nullopt;
}

} // namespace

std::optional<SinkProblem> checkSinkOptions(const SinkOptions &options)
{
    switch (options.kind) {
    case SinkKind::Y4m:
    case SinkKind::Raw:
    case SinkKind::Snapshot:
        return checkFilePath(options);
    case SinkKind::V4l2Output: // a device that may appear later (hot plug): only its name is checked here
        return options.path.empty() ? std::optional(SinkProblem{"path", "a v4l2 sink needs a device path"})
                                    : std::nullopt;
    case SinkKind::Null:
        return std::nullopt;
    }
    return std::nullopt;
}

Result<std::unique_ptr<FrameSink>> makeSink(const SinkOptions &options)
{
    if (const auto problem = checkSinkOptions(options))
        return makeError(ErrorCode::ConfigError, problem->key + ": " + problem->message);
    switch (options.kind) {
    case SinkKind::Y4m:
        return makeY4mSink(options);
    case SinkKind::Raw:
        return makeRawSink(options);
    case SinkKind::Snapshot:
        return makeSnapshotSink(options);
    case SinkKind::Null:
        return makeNullSink(options);
    case SinkKind::V4l2Output:
        return makeV4l2OutputSink(options);
    }
    return makeError(ErrorCode::InvalidArgument, "unknown sink kind");
}

} // namespace overlayd
