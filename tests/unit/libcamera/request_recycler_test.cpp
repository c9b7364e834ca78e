// SPDX-License-Identifier: Apache-2.0
// RequestRecycler: each give-back re-queues its request once, from any thread; none after detach(); a failed
// re-queue is reported once.
#include <atomic>
#include <cerrno>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "drivers/libcamera/request_recycler.h"

namespace overlayd {
namespace {

struct QueueLog {
    std::mutex mutex;
    std::vector<unsigned> queued;
    int answer = 0;

    std::function<int(unsigned)> seam()
    {
        return [this](unsigned index) {
            std::lock_guard lock(mutex);
            queued.push_back(index);
            return answer;
        };
    }
};

TEST(RequestRecycler, GiveBackRequeuesTheRequestOnce)
{
    QueueLog log;
    RequestRecycler recycler(log.seam());
    recycler.lend();
    recycler.lend();
    EXPECT_EQ(recycler.lent(), 2u);
    recycler.giveBack(3);
    EXPECT_EQ(log.queued, std::vector<unsigned>{3});
    EXPECT_EQ(recycler.lent(), 1u);
    EXPECT_FALSE(recycler.takeError().has_value());
}

TEST(RequestRecycler, NothingIsQueuedAfterDetach)
{
    QueueLog log;
    RequestRecycler recycler(log.seam());
    recycler.lend();
    recycler.detach();
    recycler.giveBack(1);
    EXPECT_TRUE(log.queued.empty());
    EXPECT_EQ(recycler.lent(), 0u);
}

TEST(RequestRecycler, AFailedRequeueIsReportedOnceAsDeviceLost)
{
    QueueLog log;
    log.answer = -ENODEV;
    RequestRecycler recycler(log.seam());
    recycler.giveBack(0);
    recycler.giveBack(1);
    const auto error = recycler.takeError();
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(error->code, ErrorCode::DeviceLost);
    EXPECT_NE(error->message.find("request 0"), std::string::npos);
    EXPECT_FALSE(recycler.takeError().has_value());
}

TEST(RequestRecycler, GiveBacksFromManyThreadsEachQueueOnce)
{
    QueueLog log;
    RequestRecycler recycler(log.seam());
    constexpr unsigned kThreads = 4, kEach = 500;
    for (unsigned i = 0; i < kThreads * kEach; ++i)
        recycler.lend();
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (unsigned i = 0; i < kEach; ++i)
                recycler.giveBack(t * kEach + i);
        });
    for (std::thread &thread : threads)
        thread.join();
    EXPECT_EQ(log.queued.size(), size_t(kThreads * kEach));
    EXPECT_EQ(recycler.lent(), 0u);
}

} // namespace
} // namespace overlayd
