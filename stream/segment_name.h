// SPDX-License-Identifier: Apache-2.0
// Segment file names: the UTC time the segment started, sortable as text ("20261127T145700Z.mp4"), with a
// ".partial" suffix while it is being written; "-1", "-2" ... when a second segment starts within the same second
// (a restart).
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace overlayd {

using WallClock = std::chrono::system_clock;

inline constexpr std::string_view kPartialSuffix = ".partial";

// "20261127T145700Z.mp4", or "20261127T145700Z-2.mp4" for repeat 2.
std::string segmentFileName(WallClock::time_point start, std::string_view extension, unsigned repeat = 0);
std::string partialFileName(std::string_view finalName);

// A file name the recorder wrote: its start time (whole seconds), and whether it is still a partial one.
struct SegmentFile {
    std::string finalName; // without ".partial"
    WallClock::time_point start;
    unsigned repeat = 0; // the "-N" of a second segment within one second
    bool partial = false;

    // Oldest first: by start, then by repeat.
    bool before(const SegmentFile &other) const
    {
        return start != other.start ? start < other.start : repeat < other.repeat;
    }
};
// nullopt for any other file: the recorder never touches what it did not write.
std::optional<SegmentFile> parseSegmentFileName(std::string_view name, std::string_view extension);

} // namespace overlayd
