// SPDX-License-Identifier: Apache-2.0
// SinkWorker: a slow sink never stalls the producer; the drop policy picks which frames are lost and counts them;
// a lossless worker waits instead; close() writes everything queued.
#include "daemon/sink_worker.h"

#include <thread>

#include <gtest/gtest.h>

#include "fakes.h"

namespace overlayd {
namespace {

using test::RecordingSink;

struct WorkerTest : ::testing::Test {
    std::shared_ptr<RecordingSink::Shared> shared = std::make_shared<RecordingSink::Shared>();
    Logger logger{[](std::string_view) {}, true};
    StreamFormat format = test::greyFormat();
    FrameBuffer frame = std::move(FrameBuffer::allocate(format).value());

    std::unique_ptr<SinkWorker> makeWorker(DropPolicy policy, bool lossless = false)
    {
        SinkOptions options;
        options.queueDepth = 4;
        options.dropPolicy = policy;
        return std::make_unique<SinkWorker>(std::make_unique<RecordingSink>(shared, "recording"), options, logger,
                                            lossless);
    }

    void push(SinkWorker &worker, uint8_t value)
    {
        frame.data()[0] = value;
        FrameMetadata metadata;
        metadata.sequence = value;
        worker.push(frame.view(), metadata);
    }

    // Frame 0 is stuck inside write() before the others arrive, so the queue arithmetic is deterministic.
    void pushBehindStuckWrite(SinkWorker &worker, int count)
    {
        shared->setGate(false);
        push(worker, 0);
        shared->waitEntered(1);
        for (int i = 1; i < count; ++i)
            push(worker, uint8_t(i));
    }
};

TEST_F(WorkerTest, SlowSinkDropsOldestAndKeepsTheNewest)
{
    auto worker = makeWorker(DropPolicy::DropOldest);
    ASSERT_TRUE(worker->open(format).ok());
    pushBehindStuckWrite(*worker, 20);          // returns although the sink is blocked: the producer is not stalled
    EXPECT_EQ(worker->counters().dropped, 15u); // 20 frames - 1 being written - 4 queued
    shared->setGate(true);
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->firstBytes, (std::vector<uint8_t>{0, 16, 17, 18, 19}));
    EXPECT_EQ(worker->counters().written, 5u);
}

TEST_F(WorkerTest, SlowSinkDropsNewestAndKeepsTheOldest)
{
    auto worker = makeWorker(DropPolicy::DropNewest);
    ASSERT_TRUE(worker->open(format).ok());
    pushBehindStuckWrite(*worker, 20);
    EXPECT_EQ(worker->counters().dropped, 15u);
    shared->setGate(true);
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->firstBytes, (std::vector<uint8_t>{0, 1, 2, 3, 4}));
}

TEST_F(WorkerTest, QueueHoldsCopiesNotTheSourcesMemory)
{
    auto worker = makeWorker(DropPolicy::DropOldest);
    ASSERT_TRUE(worker->open(format).ok());
    pushBehindStuckWrite(*worker, 3);
    frame.data()[0] = 99; // the source reuses its buffer; queued frames must not change
    shared->setGate(true);
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->firstBytes, (std::vector<uint8_t>{0, 1, 2}));
}

TEST_F(WorkerTest, LosslessWorkerWaitsInsteadOfDropping)
{
    auto worker = makeWorker(DropPolicy::DropOldest, /*lossless=*/true);
    ASSERT_TRUE(worker->open(format).ok());
    shared->setGate(false);
    std::thread producer([&] {
        for (int i = 0; i < 12; ++i)
            push(*worker, uint8_t(i));
    });
    shared->waitEntered(1);
    shared->setGate(true);
    producer.join();
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(worker->counters().dropped, 0u);
    ASSERT_EQ(shared->firstBytes.size(), 12u);
    for (int i = 0; i < 12; ++i)
        EXPECT_EQ(shared->firstBytes[i], i);
}

TEST_F(WorkerTest, CloseFlushesEveryQueuedFrameAndClosesTheSinkOnce)
{
    auto worker = makeWorker(DropPolicy::DropOldest);
    ASSERT_TRUE(worker->open(format).ok());
    for (int i = 0; i < 3; ++i)
        push(*worker, uint8_t(i));
    ASSERT_TRUE(worker->close().ok());
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->written(), 3u);
    EXPECT_EQ(shared->opens, 1);
    EXPECT_EQ(shared->closes, 1);
}

TEST_F(WorkerTest, FrameOfAnotherSizeIsRefusedAndCounted)
{
    auto worker = makeWorker(DropPolicy::DropOldest);
    ASSERT_TRUE(worker->open(format).ok());
    FrameBuffer other = std::move(FrameBuffer::allocate(test::greyFormat(32, 16)).value());
    worker->push(other.view(), FrameMetadata{});
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(worker->counters().failed, 1u);
    EXPECT_EQ(shared->written(), 0u);
}

// Copy slots are allocated when the queue first needs them: a sink that has written each frame before the next
// arrives holds one; a stuck one grows to queue_depth + 1 and no further.
TEST_F(WorkerTest, PoolGrowsOnlyAsFarAsTheQueueGets)
{
    auto worker = makeWorker(DropPolicy::DropOldest);
    ASSERT_TRUE(worker->open(format).ok());
    EXPECT_EQ(worker->allocatedFrames(), 0u);
    for (int i = 0; i < 10; ++i) {
        push(*worker, uint8_t(i));
        shared->waitEntered(i + 1);
        while (worker->counters().written < unsigned(i + 1))
            std::this_thread::yield();
    }
    EXPECT_EQ(worker->allocatedFrames(), 1u);
    pushBehindStuckWrite(*worker, 20);
    EXPECT_EQ(worker->allocatedFrames(), 5u); // 1 being written + queue_depth 4
    shared->setGate(true);
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->written(), 15u); // the 10, then 1 + the 4 newest of 20
}

TEST_F(WorkerTest, LosslessWorkerGrowsItsPoolBeforeItWaits)
{
    auto worker = makeWorker(DropPolicy::DropOldest, /*lossless=*/true);
    ASSERT_TRUE(worker->open(format).ok());
    shared->setGate(false);
    for (int i = 0; i < 5; ++i)
        push(*worker, uint8_t(i)); // would block at the first without room to grow
    EXPECT_EQ(worker->allocatedFrames(), 5u);
    shared->setGate(true);
    ASSERT_TRUE(worker->close().ok());
    EXPECT_EQ(shared->written(), 5u);
}

// The null sink is written on the caller's thread, from the frame itself: counted at once, nothing copied.
TEST_F(WorkerTest, NullSinkIsWrittenInlineWithoutCopies)
{
    SinkOptions options;
    options.kind = SinkKind::Null;
    SinkWorker worker(std::move(makeSink(options).value()), options, logger);
    ASSERT_TRUE(worker.open(format).ok());
    for (int i = 0; i < 7; ++i)
        push(worker, uint8_t(i));
    EXPECT_EQ(worker.counters().written, 7u); // no waiting: written before push() returned
    EXPECT_EQ(worker.allocatedFrames(), 0u);
    ASSERT_TRUE(worker.close().ok());
    EXPECT_EQ(worker.counters().dropped, 0u);
}

} // namespace
} // namespace overlayd
