// SPDX-License-Identifier: Apache-2.0
// Backoff: 0.5 s doubling to an 8 s ceiling, back to 0.5 s after a success.
#include "base/backoff.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

using std::chrono::milliseconds;

TEST(Backoff, DoublesUpToTheCeiling)
{
    Backoff backoff;
    const long expected[] = {500, 1000, 2000, 4000, 8000, 8000, 8000};
    for (long delay : expected)
        EXPECT_EQ(backoff.next(), milliseconds(delay));
    EXPECT_EQ(backoff.attempts(), 7u);
}

TEST(Backoff, ResetStartsOverFromTheFloor)
{
    Backoff backoff;
    backoff.next();
    backoff.next();
    EXPECT_EQ(backoff.peek(), milliseconds(2000));
    backoff.reset();
    EXPECT_EQ(backoff.attempts(), 0u);
    EXPECT_EQ(backoff.next(), milliseconds(500));
}

TEST(Backoff, CeilingBelowTheFloorIsTheFloor)
{
    Backoff backoff(milliseconds(300), milliseconds(100));
    EXPECT_EQ(backoff.next(), milliseconds(300));
    EXPECT_EQ(backoff.next(), milliseconds(300));
}

} // namespace
} // namespace overlayd
