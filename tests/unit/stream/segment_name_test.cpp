// SPDX-License-Identifier: Apache-2.0
// Segment names: UTC start times (references from `date -u -d @SECONDS +%Y%m%dT%H%M%SZ`), round trips, and what is
// not ours.
#include "stream/segment_name.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

WallClock::time_point at(time_t seconds)
{
    return WallClock::from_time_t(seconds);
}

TEST(SegmentName, IsTheUtcStartTime)
{
    EXPECT_EQ(segmentFileName(at(1796000000), "mp4"), "20261130T005320Z.mp4");
    EXPECT_EQ(segmentFileName(at(951782400), "mkv"), "20000229T000000Z.mkv");
    // Fractions of a second do not show: the name is the second the segment started in.
    EXPECT_EQ(segmentFileName(at(1795791420) + std::chrono::milliseconds(999), "mp4"), "20261127T145700Z.mp4");
    EXPECT_EQ(segmentFileName(at(1795791420), "mp4", 2), "20261127T145700Z-2.mp4");
    EXPECT_EQ(partialFileName("20261127T145700Z.mp4"), "20261127T145700Z.mp4.partial");
}

TEST(SegmentName, ParsesWhatItWrites)
{
    const auto file = parseSegmentFileName("20261130T005320Z-3.mp4.partial", "mp4");
    ASSERT_TRUE(file);
    EXPECT_EQ(file->start, at(1796000000));
    EXPECT_EQ(file->repeat, 3u);
    EXPECT_TRUE(file->partial);
    EXPECT_EQ(file->finalName, "20261130T005320Z-3.mp4");
    const auto leap = parseSegmentFileName("20000229T000000Z.mkv", "mkv");
    ASSERT_TRUE(leap);
    EXPECT_EQ(leap->start, at(951782400));
    EXPECT_FALSE(leap->partial);
}

TEST(SegmentName, OtherFilesAreNotSegments)
{
    for (const char *name : {"20261130T005320Z.mkv", "20261130T005320Z.mp4.tmp", "notes.mp4", "20261131T000000Z.mp4",
                             "20261130T245320Z.mp4", "20261130T005320.mp4", "20261130T005320Z-.mp4",
                             "20261130T005320Z-x.mp4", "20261130T005320Z-12345678901.mp4", ".mp4", "x"})
        EXPECT_FALSE(parseSegmentFileName(name, "mp4")) << name;
}

TEST(SegmentName, OrdersByStartThenRepeat)
{
    const auto first = parseSegmentFileName("20261127T145700Z.mp4", "mp4");
    const auto second = parseSegmentFileName("20261127T145700Z-1.mp4", "mp4");
    const auto later = parseSegmentFileName("20261127T145701Z.mp4", "mp4");
    ASSERT_TRUE(first && second && later);
    EXPECT_TRUE(first->before(*second));
    EXPECT_TRUE(second->before(*later));
    EXPECT_FALSE(second->before(*first));
}

} // namespace
} // namespace overlayd
