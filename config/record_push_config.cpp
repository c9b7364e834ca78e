// SPDX-License-Identifier: Apache-2.0
// [[sink]] kind = "record" and kind = "push": the encoded sinks that write segment files and publish to a server.
// What starting them would refuse is refused here, at the key: a directory that is missing, not one, not writable
// or recorded by another sink; a URL nothing can push to.
#include <filesystem>

#include "config/config_sections.h"
#include "stream/directory_segment_store.h"
#include "stream/record_options.h"

namespace overlayd {

namespace {

// Two recordings in one directory would delete each other's segments by their own budgets.
std::string directoryIdentity(const std::string &directory)
{
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(directory, error);
    return error ? std::filesystem::path(directory).lexically_normal().string() : canonical.string();
}

} // namespace

void readRecord(TableReader &sink, const StreamOptions &sofar, RecordSinkOptions &out)
{
    const size_t before = sink.problems().size();
    if (auto directory = sink.string("directory"))
        out.directory = *directory;
    else if (!sink.has("directory"))
        sink.problem("directory", "missing: the directory the segments are written to");
    if (auto segment = sink.number("segment_s", kMinSegmentSec, kMaxSegmentSec))
        out.segmentSec = *segment;
    if (auto container = sink.choice<RecordContainer>(
            "container", {{"mp4", RecordContainer::Mp4}, {"matroska", RecordContainer::Matroska}}))
        out.container = *container;
    if (auto bytes = sink.integer("keep_bytes", 0, int64_t(kMaxKeepBytes)))
        out.keepBytes = uint64_t(*bytes);
    if (auto days = sink.number("keep_days", 0, kMaxKeepDays))
        out.keepDays = *days;
    if (sink.problems().size() != before || out.directory.empty())
        return;
    if (auto writable = DirectorySegmentStore(out.directory).checkWritable(); !writable) {
        sink.problem("directory", writable.error().message);
        return;
    }
    const std::string identity = directoryIdentity(out.directory);
    for (const EncodedSinkOptions &other : sofar.sinks)
        if (other.kind == EncodedSinkKind::Record && directoryIdentity(other.record.directory) == identity) {
            sink.problem("directory", "'" + out.directory + "' is recorded by " + other.key +
                                          " already: two recordings cannot share a directory");
            return;
        }
}

void readPush(TableReader &sink, PushSinkOptions &out)
{
    if (auto url = sink.string("url", kMaxPushUrlBytes)) {
        std::string why;
        if (auto protocol = pushProtocol(*url, why)) {
            out.url = *url;
            out.protocol = *protocol;
        } else
            sink.problem("url", why);
    } else if (!sink.has("url"))
        sink.problem("url", "missing: rtsp://, rtmp:// or srt:// and the server");
}

} // namespace overlayd
