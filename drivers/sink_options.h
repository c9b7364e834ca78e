// SPDX-License-Identifier: Apache-2.0
// What a user can configure about a frame sink, and the one factory that builds any of them.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "base/result.h"
#include "drivers/frame_sink.h"

namespace overlayd {

enum class SinkKind {
    Y4m,        // a Y4M file, or stdout with path "-" (overlayd run ... | ffplay -)
    Raw,        // raw frames back to back, rows packed
    Snapshot,   // PNG/JPEG (by extension) every `every` frames; a %d in the path numbers them, else overwritten
    Null,       // counts frames, for measurements
    V4l2Output, // a V4L2 output device (v4l2loopback, vivid's output node)
};

enum class DropPolicy { DropOldest, DropNewest };

// V4l2Output: queue the capture buffer the overlay was blended into (DMABUF import) instead of copying it. Auto:
// when the frames carry dmabuf fds and the output takes DMABUF, else copy (logged once per open); On: the same, but
// impossible is an error at open(); Off: always copy.
enum class ZeroCopy { Auto, On, Off };

struct SinkOptions {
    // A stable identity for /state and /metrics labels: the config's `name`, else "sink[N]" (its table's place).
    std::string name;
    SinkKind kind = SinkKind::Null;
    std::string path;          // file, "-" for stdout, or device
    unsigned every = 1;        // Snapshot: one image per `every` frames
    unsigned jpegQuality = 90; // Snapshot .jpg
    unsigned queueDepth = 4;   // frames waiting for this sink before the drop policy applies
    DropPolicy dropPolicy = DropPolicy::DropOldest;
    unsigned bufferCount = 4;           // V4l2Output
    ZeroCopy zeroCopy = ZeroCopy::Auto; // V4l2Output

    // Every field: a reload re-opens the sinks when any differs.
    bool operator==(const SinkOptions &) const = default;
};

// What is wrong with a sink's options, found without opening anything: `key` is the [[sink]] key it is about. The
// config loader reports it at that key and makeSink() refuses the same, so check-config and run agree. Paths: a file
// sink writes a file, a FIFO or a character device (/dev/null); an existing directory, block device or socket is
// refused, and so is a path whose folder is not a folder.
struct SinkProblem {
    std::string key;
    std::string message;
};
std::optional<SinkProblem> checkSinkOptions(const SinkOptions &options);

Result<std::unique_ptr<FrameSink>> makeSink(const SinkOptions &options);

} // namespace overlayd
