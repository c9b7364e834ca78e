// What a user can configure about a recording: one [[sink]] kind = "record", a directory of segment files.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace overlayd {

// Both keep what was written before a SIGKILL or a power cut: fragmented MP4 up to its last fragment, Matroska up
// to its last cluster.
enum class RecordContainer { Mp4, Matroska };

std::string_view containerExtension(RecordContainer container); // "mp4", "mkv"

struct RecordOptions {
    std::string key;       // the config table it came from ("sink[2]"), for messages
    std::string directory; // must exist and be writable: the recorder never creates it
    double segmentSec = 60.0;
    RecordContainer container = RecordContainer::Mp4;
    uint64_t keepBytes = 0; // 0: no limit by size
    double keepDays = 0.0;  // 0: no limit by age

    bool operator==(const RecordOptions &) const = default;
};

} // namespace overlayd
