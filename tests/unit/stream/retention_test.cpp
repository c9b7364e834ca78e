// SPDX-License-Identifier: Apache-2.0
// Retention: oldest first, by age and by bytes, never the segment being written.
#include "stream/retention.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

using std::chrono::seconds;

const WallClock::time_point kNow = WallClock::from_time_t(1795791420);

StoredSegment segment(int secondsAgo, uint64_t bytes, unsigned repeat = 0)
{
    const auto name = segmentFileName(kNow - seconds(secondsAgo), "mp4", repeat);
    return {*parseSegmentFileName(name, "mp4"), bytes};
}

std::vector<std::string> names(const std::vector<StoredSegment> &segments)
{
    std::vector<std::string> out;
    for (const auto &s : segments)
        out.push_back(s.file.finalName);
    return out;
}

TEST(Retention, NoLimitsKeepsEverything)
{
    EXPECT_TRUE(segmentsToDelete({segment(600, 100), segment(60, 100)}, 50, {}, kNow).empty());
}

TEST(Retention, BytesDeleteTheOldestFirstWhateverTheOrder)
{
    const std::vector<StoredSegment> finished = {segment(120, 100), segment(360, 100), segment(240, 100)};
    // 300 finished + 50 being written within 200: the two oldest go (360 s, then 240 s ago), leaving 100 + 50.
    EXPECT_EQ(names(segmentsToDelete(finished, 50, {200, {}}, kNow)),
              (std::vector{segmentFileName(kNow - seconds(360), "mp4"), segmentFileName(kNow - seconds(240), "mp4")}));
    // Exactly at the budget is within it.
    EXPECT_TRUE(segmentsToDelete(finished, 0, {300, {}}, kNow).empty());
}

TEST(Retention, ABudgetBelowOneSegmentKeepsOnlyTheOneBeingWritten)
{
    EXPECT_EQ(segmentsToDelete({segment(120, 100), segment(60, 100)}, 500, {10, {}}, kNow).size(), 2u);
}

TEST(Retention, WithNothingBeingWrittenTheNewestStays)
{
    // A recording that stopped keeps its last segment however small the budget, and however old.
    EXPECT_EQ(names(segmentsToDelete({segment(60, 100), segment(120, 100)}, 0, {10, {}}, kNow)),
              (std::vector{segmentFileName(kNow - seconds(120), "mp4")}));
    EXPECT_EQ(segmentsToDelete({segment(3 * 86400, 1)}, 0, {0, seconds(86400)}, kNow).size(), 0u);
}

TEST(Retention, AgeDeletesThoseThatStartedTooLongAgo)
{
    const std::vector<StoredSegment> finished = {segment(3 * 86400, 1), segment(86400 + 1, 1), segment(86400, 1),
                                                 segment(10, 1)};
    EXPECT_EQ(names(segmentsToDelete(finished, 0, {0, seconds(86400)}, kNow)),
              (std::vector{segmentFileName(kNow - seconds(3 * 86400), "mp4"),
                           segmentFileName(kNow - seconds(86400 + 1), "mp4")}));
}

TEST(Retention, TheRepeatOfASecondIsNewerThanItsFirst)
{
    const std::vector<StoredSegment> finished = {segment(60, 100, 1), segment(60, 100)};
    EXPECT_EQ(names(segmentsToDelete(finished, 0, {100, {}}, kNow)),
              (std::vector{segmentFileName(kNow - seconds(60), "mp4")}));
}

} // namespace
} // namespace overlayd
