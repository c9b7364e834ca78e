// [[sink]] kind = "record" and kind = "push": the sinks of the encoded stream, read with the other [[sink]] tables
// and kept apart from the frame sinks (they never see a frame).
#include <filesystem>

#include "config/config_sections.h"
#include "config/limits.h"
#include "encoded/directory_segment_store.h"

namespace overlayd::config {

namespace {

// Two recordings in one directory would delete each other's segments by their own budgets.
std::string directoryIdentity(const std::string &directory)
{
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(directory, error);
    return error ? std::filesystem::path(directory).lexically_normal().string() : canonical.string();
}

void readRecord(TableReader &sink, EncodedSinks &out)
{
    RecordOptions options;
    options.key = sink.path();
    const size_t before = sink.problems().size();
    if (auto directory = sink.string("directory"))
        options.directory = *directory;
    else if (!sink.has("directory"))
        sink.problem("directory", "missing: the directory the segments are written to");
    if (auto segment = sink.number("segment_s", kMinSegmentSec, kMaxSegmentSec))
        options.segmentSec = *segment;
    if (auto container = sink.choice<RecordContainer>(
            "container", {{"mp4", RecordContainer::Mp4}, {"matroska", RecordContainer::Matroska}}))
        options.container = *container;
    if (auto bytes = sink.integer("keep_bytes", 0, int64_t(kMaxKeepBytes)))
        options.keepBytes = uint64_t(*bytes);
    if (auto days = sink.number("keep_days", 0, kMaxKeepDays))
        options.keepDays = *days;
    sink.finish();
    if (sink.problems().size() != before)
        return;
    // What starting the recording would refuse, at the key: check-config and run agree.
    if (auto writable = DirectorySegmentStore(options.directory).checkWritable(); !writable) {
        sink.problem("directory", writable.error().message);
        return;
    }
    const std::string identity = directoryIdentity(options.directory);
    for (const RecordOptions &other : out.records)
        if (directoryIdentity(other.directory) == identity) {
            sink.problem("directory", "'" + options.directory + "' is recorded by " + other.key +
                                          " already: two recordings cannot share a directory");
            return;
        }
    out.records.push_back(std::move(options));
}

void readPush(TableReader &sink, EncodedSinks &out)
{
    PushOptions options;
    options.key = sink.path();
    if (auto url = sink.string("url", kMaxUrlBytes)) {
        std::string why;
        if (auto protocol = pushProtocol(*url, why)) {
            options.url = *url;
            options.protocol = *protocol;
        } else
            sink.problem("url", why);
    } else if (!sink.has("url"))
        sink.problem("url", "missing: rtsp://, rtmp:// or srt:// and the server");
    sink.finish();
    if (!options.url.empty())
        out.pushes.push_back(std::move(options));
}

} // namespace

bool readEncodedSink(TableReader &sink, EncodedSinks &out)
{
    const toml::node *kind = sink.node("kind");
    const std::optional<std::string> name = kind ? kind->value<std::string>() : std::nullopt;
    if (name == "record")
        readRecord(sink, out);
    else if (name == "push")
        readPush(sink, out);
    else
        return false;
    return true;
}

} // namespace overlayd::config
