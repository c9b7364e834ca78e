// SPDX-License-Identifier: Apache-2.0
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

// Limits of a recording's keys (docs/config.md "Limits").
inline constexpr double kMinSegmentSec = 1.0;         // segment_s: below, the keyframes are the segments
inline constexpr double kMaxSegmentSec = 86400.0;     // segment_s: a day per file
inline constexpr uint64_t kMaxKeepBytes = 1ull << 50; // keep_bytes (0: no limit): a pebibyte
inline constexpr double kMaxKeepDays = 36500.0;       // keep_days (0: no limit)

struct RecordSinkOptions {
    std::string directory; // must exist and be writable: the recorder never creates it
    double segmentSec = 60.0;
    RecordContainer container = RecordContainer::Mp4;
    uint64_t keepBytes = 0; // 0: no limit by size
    double keepDays = 0.0;  // 0: no limit by age

    bool operator==(const RecordSinkOptions &) const = default;
};

} // namespace overlayd
