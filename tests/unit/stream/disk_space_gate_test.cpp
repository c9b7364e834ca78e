// SPDX-License-Identifier: Apache-2.0
// The full-disk policy: stop once, resume when a segment fits again.
#include "stream/disk_space_gate.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

TEST(DiskSpaceGate, StopsOnceAndResumesWhenASegmentFits)
{
    DiskSpaceGate gate;
    EXPECT_FALSE(gate.spaceReturned(1u << 30, 0)); // running: nothing to resume
    EXPECT_TRUE(gate.noSpace());
    EXPECT_FALSE(gate.noSpace()); // the muxer's second error about the same write: one log line, one stop
    EXPECT_TRUE(gate.stopped());
    EXPECT_EQ(gate.stops(), 1u);
    const uint64_t segment = 5u << 20;
    EXPECT_FALSE(gate.spaceReturned(segment - 1, segment));
    EXPECT_TRUE(gate.spaceReturned(segment, segment));
    EXPECT_FALSE(gate.stopped());
    EXPECT_TRUE(gate.noSpace());
    EXPECT_EQ(gate.stops(), 2u);
}

TEST(DiskSpaceGate, SmallSegmentsStillWaitForTheFloor)
{
    DiskSpaceGate gate;
    EXPECT_TRUE(gate.noSpace());
    EXPECT_FALSE(gate.spaceReturned(kMinResumeFreeBytes - 1, 1000));
    EXPECT_TRUE(gate.spaceReturned(kMinResumeFreeBytes, 1000));
}

} // namespace
} // namespace overlayd
