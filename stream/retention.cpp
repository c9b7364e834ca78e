// SPDX-License-Identifier: Apache-2.0
// Retention by age, then by bytes, always from the oldest end.
#include "stream/retention.h"

#include <algorithm>

namespace overlayd {

std::vector<StoredSegment> segmentsToDelete(std::vector<StoredSegment> finished, uint64_t currentBytes,
                                            const RetentionLimits &limits, WallClock::time_point now)
{
    std::sort(finished.begin(), finished.end(),
              [](const StoredSegment &a, const StoredSegment &b) { return a.file.before(b.file); });
    uint64_t total = currentBytes;
    for (const StoredSegment &segment : finished)
        total += segment.bytes;
    size_t count = 0;
    // With nothing being written, the newest finished segment stays: a recording always keeps its latest minutes.
    const size_t deletable = currentBytes > 0 || finished.empty() ? finished.size() : finished.size() - 1;
    for (const StoredSegment &segment : finished) {
        if (count == deletable)
            break;
        const bool tooOld = limits.keepAge.count() > 0 && segment.file.start < now - limits.keepAge;
        const bool overBudget = limits.keepBytes > 0 && total > limits.keepBytes;
        if (!tooOld && !overBudget)
            break;
        total -= segment.bytes;
        ++count;
    }
    finished.resize(count);
    return finished;
}

} // namespace overlayd
