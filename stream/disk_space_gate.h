// SPDX-License-Identifier: Apache-2.0
// DiskSpaceGate: the full-disk policy of a recording. A write that finds no space stops the recording (the stream
// and the other sinks go on); it starts again once the directory has room for a segment like the largest so far.
#pragma once

#include <cstdint>

namespace overlayd {

// Never resume with less free than this, however small the segments: a filesystem this full fails again at once.
inline constexpr uint64_t kMinResumeFreeBytes = 1u << 20;

class DiskSpaceGate
{
public:
    // A write failed for lack of space. True when the recording was running: the caller stops it and logs once.
    bool noSpace();
    // While stopped, the free bytes of the directory: true when they are back (the caller starts a new segment).
    bool spaceReturned(uint64_t freeBytes, uint64_t largestSegmentBytes);

    bool stopped() const { return stopped_; }
    unsigned stops() const { return stops_; } // since start, for /metrics
    static uint64_t resumeBytes(uint64_t largestSegmentBytes);

private:
    bool stopped_ = false;
    unsigned stops_ = 0;
};

} // namespace overlayd
