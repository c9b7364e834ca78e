// SPDX-License-Identifier: Apache-2.0
// JpegEncoder on a steady stream: once a frame size has been seen, the next frames of that size reuse the scratch
// planes and output buffer (no operator new at all on our side) and give the same bytes for the same frame.
#include "media/jpeg/jpeg_encoder.h"

#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "jpeg_test_frames.h"

// Every operator new of this test binary is counted; libjpeg's own per-image pools use malloc and are not ours.
namespace {
std::atomic<size_t> allocations{0};
} // namespace

void *operator new(size_t size)
{
    ++allocations;
    if (void *p = std::malloc(size ? size : 1))
        return p;
    throw std::bad_alloc();
}
void operator delete(void *p) noexcept
{
    std::free(p);
}
void operator delete(void *p, size_t) noexcept
{
    std::free(p);
}

namespace overlayd {
namespace {

struct SteadyCase {
    const char *format;
    Colorimetry colorimetry;
};

// One case per path: range tables (YUYV, NV12), the matrix (BT.709), planes in place (full-range I420), RGB.
constexpr SteadyCase kCases[] = {
    {"YUYV", {YcbcrMatrix::Bt601, ColourRange::Limited}}, {"YUYV", {YcbcrMatrix::Bt709, ColourRange::Limited}},
    {"NV12", {YcbcrMatrix::Bt601, ColourRange::Limited}}, {"YUV420", {YcbcrMatrix::Bt601, ColourRange::Full}},
    {"RGB24", {YcbcrMatrix::Bt601, ColourRange::Full}},
};

TEST(JpegEncoderSteadyState, SameSizeFramesAllocateNothingAndGiveTheSameBytes)
{
    auto encoder = JpegEncoder::create();
    ASSERT_TRUE(encoder);
    for (const SteadyCase &c : kCases) {
        SCOPED_TRACE(c.format);
        FrameBuffer frame = test::patternFrame(c.format, 320, 240, c.colorimetry);
        std::vector<uint8_t> first, again;
        ASSERT_TRUE(encoder->encode(frame.view(), c.colorimetry, 90, first));
        ASSERT_TRUE(encoder->encode(frame.view(), c.colorimetry, 90, again)); // sizes `again`
        const std::array<const uint8_t *, 3> scratch{encoder->planes().scratch(0), encoder->planes().scratch(1),
                                                     encoder->planes().scratch(2)};

        const size_t before = allocations.load();
        for (int i = 0; i < 3; ++i)
            ASSERT_TRUE(encoder->encode(frame.view(), c.colorimetry, 90, again));
        EXPECT_EQ(allocations.load() - before, 0u);
        EXPECT_EQ(again, first);
        for (unsigned p = 0; p < 3; ++p)
            EXPECT_EQ(encoder->planes().scratch(p), scratch[p]) << "plane " << p;
    }
}

// A smaller frame after a larger one keeps the buffers too (vectors only grow), and still decodes right.
TEST(JpegEncoderSteadyState, SmallerFramesReuseTheBuffers)
{
    auto encoder = JpegEncoder::create();
    ASSERT_TRUE(encoder);
    const Colorimetry colorimetry{};
    FrameBuffer large = test::patternFrame("YUYV", 320, 240, colorimetry);
    FrameBuffer small = test::patternFrame("YUYV", 256, 160, colorimetry);
    std::vector<uint8_t> jpeg;
    ASSERT_TRUE(encoder->encode(large.view(), colorimetry, 90, jpeg));
    const size_t before = allocations.load();
    ASSERT_TRUE(encoder->encode(small.view(), colorimetry, 90, jpeg));
    EXPECT_EQ(allocations.load() - before, 0u);
    EXPECT_EQ(test::readHeader(jpeg).width, 256);
    EXPECT_LT(test::worstChannel(test::meanError(jpeg, small.view(), colorimetry)), 3.0);
}

} // namespace
} // namespace overlayd
