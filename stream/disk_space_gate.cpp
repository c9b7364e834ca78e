// SPDX-License-Identifier: Apache-2.0
// Stopped until a segment fits again.
#include "stream/disk_space_gate.h"

#include <algorithm>

namespace overlayd {

bool DiskSpaceGate::noSpace()
{
    if (stopped_)
        return false;
    stopped_ = true;
    ++stops_;
    return true;
}

bool DiskSpaceGate::spaceReturned(uint64_t freeBytes, uint64_t largestSegmentBytes)
{
    if (!stopped_ || freeBytes < resumeBytes(largestSegmentBytes))
        return false;
    stopped_ = false;
    return true;
}

uint64_t DiskSpaceGate::resumeBytes(uint64_t largestSegmentBytes)
{
    return std::max(kMinResumeFreeBytes, largestSegmentBytes);
}

} // namespace overlayd
