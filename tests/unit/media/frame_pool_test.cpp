// SPDX-License-Identifier: Apache-2.0
// FramePool: frames are allocated as the pipeline holds them, up to the capacity, and a lease gives its frame back
// even after the source let go of the pool.
#include "media/frame_pool.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

StreamFormat grey()
{
    StreamFormat format;
    format.format = pixelFormatFromName("GREY");
    format.width = 64;
    format.height = 48;
    return format;
}

TEST(FramePool, OneFrameServesAPipelineThatGivesEachBack)
{
    auto pool = FramePool::create(grey(), 4);
    ASSERT_TRUE(pool);
    for (int i = 0; i < 10; ++i) {
        const auto index = (*pool)->acquire();
        ASSERT_TRUE(index);
        FrameLease lease = (*pool)->lend(*index, FrameMetadata{});
        EXPECT_EQ(lease.view().planes[0].data, (*pool)->buffer(0).data()); // the same frame every time
    }
    EXPECT_EQ((*pool)->allocated(), 1u);
}

TEST(FramePool, GrowsToItsCapacityWhileFramesAreHeldAndNoFurther)
{
    auto pool = FramePool::create(grey(), 3);
    ASSERT_TRUE(pool);
    std::vector<FrameLease> held;
    for (int i = 0; i < 3; ++i) {
        const auto index = (*pool)->acquire();
        ASSERT_TRUE(index);
        held.push_back((*pool)->lend(*index, FrameMetadata{}));
    }
    EXPECT_EQ((*pool)->allocated(), 3u);
    EXPECT_FALSE((*pool)->acquire()); // all lent out: the source says TryAgain
    held.pop_back();
    EXPECT_TRUE((*pool)->acquire());
    EXPECT_EQ((*pool)->allocated(), 3u);
}

TEST(FramePool, ALeaseOutlivesThePool)
{
    auto pool = FramePool::create(grey(), 2);
    ASSERT_TRUE(pool);
    FrameLease lease = (*pool)->lend(*(*pool)->acquire(), FrameMetadata{});
    pool->reset();                      // the source stopped
    lease.view().planes[0].data[0] = 7; // still the pool's memory, kept alive by the lease
    lease.reset();
}

TEST(FramePool, RefusesAFormatWithoutPixels)
{
    EXPECT_FALSE(FramePool::create(StreamFormat{}, 4));
}

} // namespace
} // namespace overlayd
