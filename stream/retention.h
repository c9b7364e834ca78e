// SPDX-License-Identifier: Apache-2.0
// Retention: which finished segments to delete, oldest first, to keep a recording within its byte and age budgets.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "stream/segment_name.h"

namespace overlayd {

struct RetentionLimits {
    uint64_t keepBytes = 0;         // 0: no limit
    std::chrono::seconds keepAge{}; // 0: no limit
};

struct StoredSegment {
    SegmentFile file;
    uint64_t bytes = 0;
};

// The finished segments to delete, oldest first: every one that started more than keepAge before `now`, then the
// oldest until the rest and the segment being written (`currentBytes`) fit in keepBytes. The segment being written
// is never among them, so a budget smaller than one segment keeps just that one; with nothing being written
// (currentBytes 0) the newest finished one is kept instead.
std::vector<StoredSegment> segmentsToDelete(std::vector<StoredSegment> finished, uint64_t currentBytes,
                                            const RetentionLimits &limits, WallClock::time_point now);

} // namespace overlayd
