// SPDX-License-Identifier: Apache-2.0
// RequestSlots: the deadlines count from a phase's start whatever happens meanwhile, and a newcomer always finds
// room by closing the slowest incomplete request (of its address, then of all), never a stream or an answer.
#include "http/request_slots.h"

#include <gtest/gtest.h>

using namespace overlayd;
using Clock = RequestSlots::Clock;
using std::chrono::seconds;

namespace {

const Clock::time_point t0 = Clock::now();

SlotLimits limits(unsigned perAddress, unsigned total)
{
    return SlotLimits{perAddress, total, std::chrono::milliseconds(10000), std::chrono::milliseconds(20000)};
}

} // namespace

TEST(RequestSlots, HeaderAndBodyDeadlinesCountFromThePhasesStart)
{
    RequestSlots slots(limits(8, 32));
    (void)slots.opened(1, "a", t0);
    (void)slots.opened(2, "a", t0);
    slots.phase(2, RequestSlots::Phase::Body, t0 + seconds(5));
    EXPECT_TRUE(slots.late(t0 + seconds(9)).empty());
    const auto headers = slots.late(t0 + seconds(10));
    ASSERT_EQ(headers.size(), 1u);
    EXPECT_EQ(headers[0], std::make_pair(RequestSlots::Id(1), ShedReason::HeaderDeadline));
    EXPECT_TRUE(slots.late(t0 + seconds(24)).empty()) << "each late request is returned once";
    const auto body = slots.late(t0 + seconds(25));
    ASSERT_EQ(body.size(), 1u);
    EXPECT_EQ(body[0], std::make_pair(RequestSlots::Id(2), ShedReason::BodyDeadline));
    EXPECT_EQ(slots.shedCount(ShedReason::HeaderDeadline), 1u);
    EXPECT_EQ(slots.shedCount(ShedReason::BodyDeadline), 1u);
}

TEST(RequestSlots, ServingHasNoDeadlineAndAKeptAliveConnectionStartsAgain)
{
    RequestSlots slots(limits(8, 32));
    (void)slots.opened(1, "a", t0);
    slots.phase(1, RequestSlots::Phase::Serving, t0 + seconds(1));
    EXPECT_TRUE(slots.late(t0 + seconds(100)).empty());
    slots.phase(1, RequestSlots::Phase::Headers, t0 + seconds(100));
    EXPECT_TRUE(slots.late(t0 + seconds(109)).empty());
    EXPECT_EQ(slots.late(t0 + seconds(110)).size(), 1u);
}

TEST(RequestSlots, AnAddressAtItsCapLosesItsSlowestRequest)
{
    RequestSlots slots(limits(2, 32));
    (void)slots.opened(1, "a", t0);
    (void)slots.opened(2, "a", t0 + seconds(1));
    (void)slots.opened(3, "b", t0 + seconds(2));
    const auto shed = slots.opened(4, "a", t0 + seconds(3));
    ASSERT_EQ(shed.size(), 1u);
    EXPECT_EQ(shed[0], std::make_pair(RequestSlots::Id(1), ShedReason::PerAddress));
    EXPECT_TRUE(slots.opened(5, "b", t0 + seconds(4)).empty()) << "another address has its own cap";
}

TEST(RequestSlots, WhenFullTheSlowestIncompleteGoesNeverAStream)
{
    RequestSlots slots(limits(8, 3));
    (void)slots.opened(1, "a", t0);
    slots.phase(1, RequestSlots::Phase::Serving, t0); // a stream, the oldest
    (void)slots.opened(2, "b", t0 + seconds(1));
    (void)slots.opened(3, "c", t0 + seconds(2));
    auto shed = slots.opened(4, "d", t0 + seconds(3));
    ASSERT_EQ(shed.size(), 1u);
    EXPECT_EQ(shed[0], std::make_pair(RequestSlots::Id(2), ShedReason::Total));
    slots.closed(2);
    slots.phase(3, RequestSlots::Phase::Serving, t0 + seconds(4));
    slots.phase(4, RequestSlots::Phase::Serving, t0 + seconds(4));
    shed = slots.opened(5, "e", t0 + seconds(5));
    ASSERT_EQ(shed.size(), 1u) << "every slot serves: the newcomer is refused";
    EXPECT_EQ(shed[0], std::make_pair(RequestSlots::Id(5), ShedReason::Total));
}

TEST(RequestSlots, ABurstFromOneAddressIsNotShedBeforeItCouldSpeak)
{
    RequestSlots slots(limits(2, 32));
    (void)slots.opened(1, "a", t0);
    (void)slots.opened(2, "a", t0);
    EXPECT_TRUE(slots.opened(3, "a", t0).empty()) << "requests accepted in one pass, none read yet";
    const auto shed = slots.opened(4, "a", t0 + seconds(1));
    EXPECT_EQ(shed.size(), 2u) << "a second later the older ones are slow";
}
