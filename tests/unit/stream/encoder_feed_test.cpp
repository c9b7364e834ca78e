// SPDX-License-Identifier: Apache-2.0
// EncoderFeed: the one copy for the encoder, to I420, checked against the frame's own samples; slots bounded, a
// frame that finds none dropped and counted, a slot given back when its last holder lets go (from any thread).
#include <gtest/gtest.h>

#include <thread>

#include "media/frame_buffer.h"
#include "stream/encoder_feed.h"

using namespace overlayd;

namespace {

StreamFormat formatOf(const char *name, unsigned width, unsigned height)
{
    StreamFormat format;
    format.format = pixelFormatFromName(name);
    format.width = width, format.height = height, format.fps = 30;
    return format;
}

// A frame whose Y, Cb and Cr samples are known: Y = x + y, chroma constant.
FrameBuffer i420Frame(unsigned width, unsigned height)
{
    FrameBuffer frame = std::move(*FrameBuffer::allocate(formatOf("YUV420", width, height)));
    const FrameView view = frame.view();
    for (unsigned y = 0; y < height; ++y)
        for (unsigned x = 0; x < width; ++x)
            view.planes[0].data[size_t(y) * view.planes[0].stride + x] = uint8_t(x + y);
    for (unsigned y = 0; y < height / 2; ++y)
        for (unsigned x = 0; x < width / 2; ++x) {
            view.planes[1].data[size_t(y) * view.planes[1].stride + x] = 90;
            view.planes[2].data[size_t(y) * view.planes[2].stride + x] = 200;
        }
    return frame;
}

TEST(EncoderFeed, CopiesI420PlanesUnconverted)
{
    EncoderFeed feed(2);
    ASSERT_TRUE(feed.open(formatOf("YUV420", 8, 4)));
    FrameBuffer frame = i420Frame(8, 4);
    FrameMetadata metadata;
    metadata.sequence = 7;
    auto input = feed.fill(frame.view(), metadata, std::chrono::nanoseconds(5));
    ASSERT_TRUE(input);
    ASSERT_EQ(input->size, 8u * 4 * 3 / 2);
    EXPECT_EQ(input->sequence, 7u);
    EXPECT_EQ(input->data[3 * 8 + 5], 8);    // Y at (5, 3)
    EXPECT_EQ(input->data[32], 90);          // first Cb
    EXPECT_EQ(input->data[32 + 8 + 7], 200); // last Cr
    EXPECT_EQ(feed.counters().copied, 1u);
    EXPECT_EQ(feed.counters().converted, 0u);
}

TEST(EncoderFeed, ConvertsYuyvToI420AndCountsIt)
{
    EncoderFeed feed(1);
    ASSERT_TRUE(feed.open(formatOf("YUYV", 4, 2)));
    FrameBuffer frame = std::move(*FrameBuffer::allocate(formatOf("YUYV", 4, 2)));
    // Two rows of Y0 Cb Y1 Cr: Cb 100/120 and Cr 150/170 on the two rows, so 4:2:0 averages them.
    const uint8_t rows[2][8] = {{10, 100, 11, 150, 12, 100, 13, 150}, {20, 120, 21, 170, 22, 120, 23, 170}};
    for (unsigned y = 0; y < 2; ++y)
        std::copy(rows[y], rows[y] + 8, frame.view().planes[0].data + size_t(y) * frame.view().planes[0].stride);
    auto input = feed.fill(frame.view(), {}, {});
    ASSERT_TRUE(input);
    const uint8_t expectedY[8] = {10, 11, 12, 13, 20, 21, 22, 23};
    EXPECT_TRUE(std::equal(expectedY, expectedY + 8, input->data));
    EXPECT_EQ(input->data[8], 110);  // Cb of the left macropixel: (100 + 120) / 2
    EXPECT_EQ(input->data[10], 160); // Cr: (150 + 170) / 2
    EXPECT_EQ(feed.counters().converted, 1u);
}

TEST(EncoderFeed, DropsWhenEverySlotIsWithTheEncoderAndReusesReleasedOnes)
{
    EncoderFeed feed(2);
    ASSERT_TRUE(feed.open(formatOf("YUV420", 8, 4)));
    FrameBuffer frame = i420Frame(8, 4);
    auto first = feed.fill(frame.view(), {}, {});
    auto second = feed.fill(frame.view(), {}, {});
    ASSERT_TRUE(first && second);
    EXPECT_FALSE(feed.fill(frame.view(), {}, {})); // both slots held: dropped, never waited for
    EXPECT_EQ(feed.counters().dropped, 1u);
    EXPECT_EQ(feed.counters().inFlight, 2u);
    const uint8_t *firstBytes = first->data;
    // The encoder lets go of the first frame on its own thread (a GStreamer buffer's destroy notify).
    std::thread([held = std::move(*first)]() mutable { held.owner.reset(); }).join();
    first.reset();
    EXPECT_EQ(feed.counters().inFlight, 1u);
    auto third = feed.fill(frame.view(), {}, {});
    ASSERT_TRUE(third);
    EXPECT_EQ(third->data, firstBytes); // the slot that came back
    EXPECT_EQ(feed.counters().copied, 3u);
}

TEST(EncoderFeed, ASlotOutlivesTheFeed)
{
    std::shared_ptr<void> owner;
    const uint8_t *data = nullptr;
    {
        EncoderFeed feed(1);
        ASSERT_TRUE(feed.open(formatOf("YUV420", 8, 4)));
        FrameBuffer frame = i420Frame(8, 4);
        auto kept = feed.fill(frame.view(), {}, {});
        ASSERT_TRUE(kept);
        owner = kept->owner, data = kept->data;
    }
    EXPECT_EQ(data[0], 0); // still readable: the slot holds the pool
    owner.reset();         // and its release after the feed is gone touches nothing freed (ASan says)
}

TEST(EncoderFeed, RefusesOddSizesAndReopeningWhileTheEncoderHoldsFrames)
{
    EncoderFeed feed(1);
    EXPECT_FALSE(feed.open(formatOf("YUV420", 7, 4)));
    ASSERT_TRUE(feed.open(formatOf("YUV420", 8, 4)));
    FrameBuffer frame = i420Frame(8, 4);
    auto held = feed.fill(frame.view(), {}, {});
    ASSERT_TRUE(held);
    auto reopened = feed.open(formatOf("YUV420", 16, 8));
    ASSERT_FALSE(reopened);
    EXPECT_NE(reopened.error().message.find("still holds 1"), std::string::npos);
    held.reset();
    EXPECT_TRUE(feed.open(formatOf("YUV420", 16, 8)));
}

} // namespace

namespace {

TEST(EncoderFeed, DeinterleavesNv12ChromaAndCountsTheConversion)
{
    EncoderFeed feed(1);
    ASSERT_TRUE(feed.open(formatOf("NV12", 4, 2)));
    FrameBuffer frame = std::move(*FrameBuffer::allocate(formatOf("NV12", 4, 2)));
    const FrameView view = frame.view();
    const uint8_t luma[2][4] = {{1, 2, 3, 4}, {5, 6, 7, 8}};
    for (unsigned y = 0; y < 2; ++y)
        std::copy(luma[y], luma[y] + 4, view.planes[0].data + size_t(y) * view.planes[0].stride);
    const uint8_t chroma[4] = {90, 200, 91, 201}; // Cb Cr Cb Cr
    std::copy(chroma, chroma + 4, view.planes[1].data);
    auto input = feed.fill(view, {}, {});
    ASSERT_TRUE(input);
    const uint8_t expected[12] = {1, 2, 3, 4, 5, 6, 7, 8, 90, 91, 200, 201};
    EXPECT_TRUE(std::equal(expected, expected + 12, input->data));
    EXPECT_EQ(feed.counters().converted, 1u);
}

} // namespace
