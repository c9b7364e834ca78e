// SPDX-License-Identifier: Apache-2.0
// The synthetic source: determinism across runs, each pattern's defining property, metadata, stalling, leases.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "drivers/source_options.h"
#include "drivers/synthetic/patterns.h"
#include "test_util.h"

namespace overlayd {
namespace {

SourceOptions options(SyntheticPattern pattern, const std::string &format, unsigned width, unsigned height)
{
    SourceOptions o;
    o.kind = SourceKind::Synthetic;
    o.pixelFormat = pixelFormatFromName(format);
    o.width = width, o.height = height, o.fps = 25.0;
    o.synthetic.pattern = pattern;
    return o;
}

std::unique_ptr<FrameSource> started(const SourceOptions &o)
{
    auto source = makeSource(o);
    EXPECT_TRUE(source) << (source ? "" : source.error().message);
    if (!source)
        return nullptr;
    auto format = (*source)->start();
    EXPECT_TRUE(format) << (format ? "" : format.error().message);
    return std::move(*source);
}

std::vector<uint64_t> hashes(const SourceOptions &o, unsigned frames)
{
    auto source = started(o);
    std::vector<uint64_t> out;
    for (unsigned i = 0; source && i < frames; ++i) {
        auto lease = source->nextFrame();
        EXPECT_TRUE(lease);
        if (lease)
            out.push_back(test::hashFrame(lease->view()));
    }
    return out;
}

TEST(Synthetic, SameSeedSameBytesAcrossRuns)
{
    SourceOptions o = options(SyntheticPattern::Noise, "NV12", 64, 48);
    o.synthetic.seed = 7;
    const auto first = hashes(o, 3), second = hashes(o, 3);
    ASSERT_EQ(first.size(), 3u);
    EXPECT_EQ(first, second);
    EXPECT_NE(first[0], first[1]); // noise changes per frame
    o.synthetic.seed = 8;
    EXPECT_NE(hashes(o, 1)[0], first[0]);
    for (SyntheticPattern p :
         {SyntheticPattern::ColourBars, SyntheticPattern::Checkerboard, SyntheticPattern::MovingGradient}) {
        const SourceOptions other = options(p, "YUYV", 64, 48);
        EXPECT_EQ(hashes(other, 2), hashes(other, 2));
    }
}

TEST(Synthetic, ColourBarsDecodeToTheirColours)
{
    auto source = started(options(SyntheticPattern::ColourBars, "YUYV", 128, 16));
    auto lease = source->nextFrame();
    ASSERT_TRUE(lease);
    const FrameView &view = lease->view();
    cv::Mat rgb;
    cv::cvtColor(cv::Mat(16, 128, CV_8UC2, view.planes[0].data, view.planes[0].stride), rgb, cv::COLOR_YUV2RGB_YUYV);
    for (unsigned bar = 0; bar < 8; ++bar) {
        const int x = int(bar * 16 + 8);
        const cv::Vec3b px = rgb.at<cv::Vec3b>(8, x);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(px[k], kBarColours[bar][k], 3) << "bar " << bar << " channel " << k;
    }
}

TEST(Synthetic, CheckerboardFlipsEveryCheckerPx)
{
    SourceOptions o = options(SyntheticPattern::Checkerboard, "RGB24", 50, 30);
    o.synthetic.checkerPx = 10;
    auto source = started(o);
    auto lease = source->nextFrame();
    ASSERT_TRUE(lease);
    const PlaneView &plane = lease->view().planes[0];
    for (unsigned y = 0; y < 30; ++y) {
        for (unsigned x = 0; x < 50; ++x) {
            const bool white = ((x / 10) + (y / 10)) % 2 == 0;
            EXPECT_EQ(plane.data[y * plane.stride + 3 * x], white ? 255 : 0) << x << "," << y;
        }
    }
}

TEST(Synthetic, MovingGradientScrollsByItsStep)
{
    auto source = started(options(SyntheticPattern::MovingGradient, "RGB24", 64, 8));
    auto first = source->nextFrame();
    ASSERT_TRUE(first);
    const std::vector<uint8_t> a = test::visibleBytes(first->view());
    first->reset();
    auto second = source->nextFrame();
    ASSERT_TRUE(second);
    const std::vector<uint8_t> b = test::visibleBytes(second->view());
    for (unsigned y = 0; y < 8; ++y) {
        for (unsigned x = 0; x + kGradientStepPx < 64; ++x) {
            for (unsigned k = 0; k < 3; ++k)
                ASSERT_EQ(b[(y * 64 + x) * 3 + k], a[(y * 64 + x + kGradientStepPx) * 3 + k]);
        }
    }
    EXPECT_NE(a, b);
}

TEST(Synthetic, MetadataCountsFramesAtFpsSpacing)
{
    auto source = started(options(SyntheticPattern::ColourBars, "GREY", 16, 16));
    EXPECT_EQ(source->eventFd(), -1);
    std::chrono::system_clock::time_point first{};
    for (uint64_t n = 0; n < 5; ++n) {
        const auto before = std::chrono::steady_clock::now().time_since_epoch();
        auto lease = source->nextFrame();
        ASSERT_TRUE(lease);
        EXPECT_EQ(lease->metadata().sequence, n);
        // Made now, on CLOCK_MONOTONIC; the printed wall clock advances by the frame period.
        EXPECT_GE(lease->metadata().timestamp, before);
        EXPECT_LE(lease->metadata().timestamp, std::chrono::steady_clock::now().time_since_epoch());
        if (n == 0)
            first = lease->metadata().wallClock;
        EXPECT_EQ(lease->metadata().wallClock - first, std::chrono::milliseconds(40 * n)); // 25 fps
    }
}

TEST(Synthetic, StallsAfterConfiguredFrames)
{
    SourceOptions o = options(SyntheticPattern::ColourBars, "YUYV", 16, 16);
    o.synthetic.stallAfterFrames = 3;
    auto source = started(o);
    for (int n = 0; n < 3; ++n)
        EXPECT_TRUE(source->nextFrame());
    for (int n = 0; n < 3; ++n) {
        auto lease = source->nextFrame();
        ASSERT_FALSE(lease);
        EXPECT_EQ(lease.error().code, ErrorCode::TryAgain);
    }
}

TEST(Synthetic, LeasesReturnTheirBuffers)
{
    auto source = started(options(SyntheticPattern::Noise, "YUV420", 16, 16));
    std::vector<FrameLease> held;
    for (;;) {
        auto lease = source->nextFrame();
        if (!lease) {
            EXPECT_EQ(lease.error().code, ErrorCode::TryAgain);
            break;
        }
        held.push_back(std::move(*lease));
        ASSERT_LT(held.size(), 64u);
    }
    EXPECT_GE(held.size(), 2u);
    held.pop_back();
    EXPECT_TRUE(source->nextFrame());
    source.reset(); // leases may outlive their source
    held.clear();
}

} // namespace
} // namespace overlayd
