// SPDX-License-Identifier: Apache-2.0
// RecordDirectory: the segments of one recording on its SegmentStore: names for new segments, the rename that
// finishes one, what a crash left behind, retention, and the figures /state and /metrics show.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "stream/record_options.h"
#include "stream/retention.h"
#include "stream/segment_store.h"

namespace overlayd {

struct RecordFigures {
    unsigned segments = 0;  // finished segments in the directory
    uint64_t bytes = 0;     // their bytes
    std::string oldest;     // the oldest one's name, empty when none
    unsigned deleted = 0;   // by retention, since start
    unsigned recovered = 0; // partial segments a crash left, finished at start
};

class RecordDirectory
{
public:
    RecordDirectory(SegmentStore &store, RecordContainer container, RetentionLimits limits);

    // At start: a partial segment a crash left is readable up to its last fragment, so it is finished under its own
    // name; an empty one (killed before its first fragment) is removed. Then retention runs.
    Status recover(WallClock::time_point now);
    // The partial file name for a segment starting at `start`, taken by no other segment, finished or not.
    std::string nextPartialName(WallClock::time_point start);
    // The segment written under `partialName` is complete: renamed to its final name (removed when empty), then
    // retention runs with nothing being written.
    Status finish(const std::string &partialName, WallClock::time_point now);
    // Retention, counting `currentBytes` being written; refreshes the figures.
    Status prune(WallClock::time_point now, uint64_t currentBytes);

    const RecordFigures &figures() const { return figures_; }
    // The largest finished segment seen: how much room the next one is likely to need.
    uint64_t largestSegmentBytes() const { return largest_; }

private:
    // The store's segments of this container, partial ones included.
    Result<std::vector<StoredSegment>> scan();
    void tally(const std::vector<StoredSegment> &finished);

    SegmentStore &store_;
    RecordContainer container_;
    RetentionLimits limits_;
    RecordFigures figures_;
    uint64_t largest_ = 0;
};

} // namespace overlayd
