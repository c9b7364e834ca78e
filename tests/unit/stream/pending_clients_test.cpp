// SPDX-License-Identifier: Apache-2.0
// PendingClients: the RTSP connections that have not asked to play, held to a cap per address and in all (the
// oldest shed for a new one) and to a deadline.
#include "stream/pending_clients.h"

#include <gtest/gtest.h>

#include <vector>

namespace overlayd {
namespace {

using namespace std::chrono_literals;
using Handle = PendingClients::Handle;

// Distinct opaque handles, as GstRTSPClient pointers would be.
const int kClients[64] = {};
Handle client(int i)
{
    return &kClients[i];
}

const PendingClients::Clock::time_point t0{};

TEST(PendingClients, UnderTheCapsNothingIsShed)
{
    PendingClients pending({.total = 4, .perAddress = 2, .deadline = 10s});
    EXPECT_TRUE(pending.admit(client(0), "10.0.0.1", t0).empty());
    EXPECT_TRUE(pending.admit(client(1), "10.0.0.1", t0).empty());
    EXPECT_TRUE(pending.admit(client(2), "10.0.0.2", t0).empty());
    EXPECT_EQ(pending.pending(), 3u);
    EXPECT_EQ(pending.shed(), 0u);
}

TEST(PendingClients, ANewConnectionOverTheAddressCapShedsThatAddresssOldest)
{
    PendingClients pending({.total = 10, .perAddress = 2, .deadline = 10s});
    pending.admit(client(0), "10.0.0.1", t0);
    pending.admit(client(1), "10.0.0.2", t0 + 1s); // another address: never shed for 10.0.0.1
    pending.admit(client(2), "10.0.0.1", t0 + 2s);
    EXPECT_EQ(pending.admit(client(3), "10.0.0.1", t0 + 3s), std::vector<Handle>{client(0)});
    EXPECT_EQ(pending.admit(client(4), "10.0.0.1", t0 + 4s), std::vector<Handle>{client(2)});
    EXPECT_EQ(pending.pending(), 3u);
    EXPECT_EQ(pending.shed(), 2u);
}

TEST(PendingClients, ANewConnectionOverTheTotalCapShedsTheOldestOfAll)
{
    PendingClients pending({.total = 3, .perAddress = 3, .deadline = 10s});
    for (int i = 0; i < 3; ++i)
        pending.admit(client(i), "10.0.0." + std::to_string(i), t0 + i * 1s);
    EXPECT_EQ(pending.admit(client(3), "10.0.0.9", t0 + 5s), std::vector<Handle>{client(0)});
    EXPECT_EQ(pending.pending(), 3u);
}

TEST(PendingClients, AClientThatPlaysOrLeavesNoLongerCounts)
{
    PendingClients pending({.total = 2, .perAddress = 2, .deadline = 10s});
    pending.admit(client(0), "10.0.0.1", t0);
    pending.admit(client(1), "10.0.0.1", t0);
    pending.started(client(0));
    pending.closed(client(1));
    EXPECT_EQ(pending.pending(), 0u);
    EXPECT_TRUE(pending.admit(client(2), "10.0.0.1", t0).empty());
    EXPECT_TRUE(pending.admit(client(3), "10.0.0.1", t0).empty());
    EXPECT_TRUE(pending.expired(t0 + 1h) == (std::vector<Handle>{client(2), client(3)}));
    EXPECT_EQ(pending.shed(), 0u);
}

TEST(PendingClients, TheDeadlineClosesThoseThatHaveNotPlayedAndOnlyThem)
{
    PendingClients pending({.total = 10, .perAddress = 10, .deadline = 10s});
    pending.admit(client(0), "10.0.0.1", t0);
    pending.admit(client(1), "10.0.0.1", t0 + 5s);
    pending.admit(client(2), "10.0.0.1", t0);
    pending.started(client(2));
    EXPECT_TRUE(pending.expired(t0 + 9s).empty());
    EXPECT_EQ(pending.expired(t0 + 10s), std::vector<Handle>{client(0)});
    EXPECT_TRUE(pending.expired(t0 + 14s).empty());
    EXPECT_EQ(pending.expired(t0 + 15s), std::vector<Handle>{client(1)});
    EXPECT_EQ(pending.timedOut(), 2u);
    EXPECT_EQ(pending.pending(), 0u);
}

TEST(PendingClients, AStormStaysWithinTheCaps)
{
    PendingClients pending; // the defaults the RTSP server runs with
    size_t shed = 0;
    for (int i = 0; i < 2000; ++i)
        shed += pending.admit(client(i % 64), "127.0.0.1", t0).size() > 0 ? 1 : 0;
    EXPECT_LE(pending.pending(), kMaxPendingRtspClientsPerAddress);
    EXPECT_EQ(pending.shed(), shed);
}

} // namespace
} // namespace overlayd
