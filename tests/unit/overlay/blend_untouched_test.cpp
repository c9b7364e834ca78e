// SPDX-License-Identifier: Apache-2.0
// The blend writes nothing outside the layer's coverage: random frames (padding included) and random sparse
// layers, byte-compared in every format, size and stride, with guard bytes after the buffer.
#include <ostream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "overlay/blend/native_layer.h"
#include "test_frames.h"

namespace overlayd {
namespace {

using test::TestFrame;

struct Case {
    std::string format;
    unsigned width, height, stridePadding;
};

std::vector<Case> allCases()
{
    std::vector<Case> cases;
    for (const PixelFormatInfo &info : pixelFormats()) {
        for (const Case &size : {Case{"", 32, 24, 0}, Case{"", 33, 17, 10}, Case{"", 1, 1, 0}, Case{"", 7, 3, 3}})
            cases.push_back({std::string(info.name), size.width, size.height, size.stridePadding});
    }
    return cases;
}

// Keeps gtest from printing the raw bytes of a case in test names.
void PrintTo(const Case &c, std::ostream *os)
{
    *os << c.format << " " << c.width << "x" << c.height << " +" << c.stridePadding;
}

std::string caseName(const testing::TestParamInfo<Case> &info)
{
    return info.param.format + "_" + std::to_string(info.param.width) + "x" + std::to_string(info.param.height) +
           "_pad" + std::to_string(info.param.stridePadding);
}

// Isolated pixels and short runs with random colour and alpha, touching the right and bottom edges.
OverlayLayer randomLayer(unsigned width, unsigned height, std::mt19937 &rng)
{
    OverlayLayer layer(width, height);
    std::uniform_int_distribution<int> byte(0, 255), x(0, width - 1), y(0, height - 1), len(1, 4);
    for (unsigned i = 0; i < width * height / 12 + 1; ++i)
        layer.fillRect(x(rng), y(rng), len(rng), 1,
                       {uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng) | 1)});
    layer.fillRect(width - 1, height - 1, 1, 1, {10, 200, 30, 255});
    layer.updateSpans();
    return layer;
}

class BlendUntouched : public testing::TestWithParam<Case>
{};

TEST_P(BlendUntouched, OnlyCoveredBytesChange)
{
    const Case &c = GetParam();
    std::mt19937 rng(1234);
    TestFrame frame = test::makeFrame(c.format, c.width, c.height, c.stridePadding);
    std::uniform_int_distribution<int> byte(0, 255);
    for (size_t i = 0; i < frame.layout.totalSize; ++i)
        frame.bytes[i] = uint8_t(byte(rng));
    const std::vector<uint8_t> before = frame.bytes;
    const OverlayLayer layer = randomLayer(c.width, c.height, rng);

    auto native = NativeLayer::convert(layer, test::format(c.format), Colorimetry{});
    ASSERT_TRUE(native);
    ASSERT_TRUE(native->blend(frame.view()));
    ASSERT_TRUE(frame.guardIntact());

    unsigned changed = 0;
    for (unsigned p = 0; p < test::format(c.format).numPlanes; ++p) {
        for (unsigned row = 0; row < test::format(c.format).planeHeight(p, c.height); ++row) {
            for (unsigned col = 0; col < frame.stride(p); ++col) {
                const size_t i = frame.layout.planes[p].offset + size_t(row) * frame.stride(p) + col;
                bool covered = false;
                for (const cv::Point &q : test::pixelsOfByte(frame, p, row, col))
                    covered = covered || layer.pixel(q.x, q.y)[3] != 0;
                if (!covered) {
                    ASSERT_EQ(frame.bytes[i], before[i]) << "plane " << p << " row " << row << " byte " << col;
                }
                changed += frame.bytes[i] != before[i];
            }
        }
    }
    EXPECT_GT(changed, 0u); // the layer covers something, so the test would see a blend that wrote nothing
}

TEST(BlendUntouched, RefusesAMismatchedFrame)
{
    OverlayLayer layer(8, 8);
    layer.fillRect(0, 0, 2, 2, {255, 0, 0, 255});
    layer.updateSpans();
    auto native = NativeLayer::convert(layer, test::format("NV12"), Colorimetry{});
    ASSERT_TRUE(native);
    TestFrame wrongSize = test::makeFrame("NV12", 8, 6, 0);
    EXPECT_FALSE(native->blend(wrongSize.view()));
    TestFrame wrongFormat = test::makeFrame("NV21", 8, 8, 0);
    EXPECT_FALSE(native->blend(wrongFormat.view()));
    TestFrame truncated = test::makeFrame("NV12", 8, 8, 0);
    FrameView view = truncated.view();
    view.planes[1].size = 0;
    const Status status = native->blend(view);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message, "NV12 plane 1 is missing or too small for 8x8");
}

INSTANTIATE_TEST_SUITE_P(AllFormats, BlendUntouched, testing::ValuesIn(allCases()), caseName);

} // namespace
} // namespace overlayd
