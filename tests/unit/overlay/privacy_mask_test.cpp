// SPDX-License-Identifier: Apache-2.0
// Privacy masks against independent references: which pixels a polygon covers (a winding number at every pixel
// centre, brute force), the fill (test_frames' own encoding of the colour, byte by byte), the pixelation (block
// averages summed here from the bytes test_frames says belong to each block) -- in every pixel format, with the
// macropixels that touch the polygon masked whole and every other byte left as it was.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "overlay/privacy_masks.h"
#include "overlay/raster/polygon_spans.h"
#include "scene_fixture.h"
#include "test_frames.h"

namespace overlayd {
namespace {

using test::TestFrame;

constexpr unsigned kWidth = 61, kHeight = 45; // odd: a last macropixel with one column and one row

// The winding number of the polygon around p, summed from the angles its edges subtend (no scanline, no crossing
// rules): nonzero inside.
bool insideByAngles(const std::vector<glm::dvec2> &polygon, glm::dvec2 p)
{
    double total = 0.0;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2 a = polygon[i] - p, b = polygon[(i + 1) % polygon.size()] - p;
        total += std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
    }
    return std::abs(std::lround(total / (2.0 * M_PI))) != 0;
}

// A concave, self-crossing outline in top-left pixel corners (a star and a notch), vertices off the pixel grid.
std::vector<glm::dvec2> starOutline()
{
    std::vector<glm::dvec2> out;
    for (int i = 0; i < 5; ++i) {
        const double angle = 2.0 * M_PI * (i * 2 % 5) / 5.0 + 0.3;
        out.push_back({30.3 + 26.1 * std::cos(angle), 22.7 + 19.4 * std::sin(angle)});
    }
    return out;
}

// Pixel (x, y) of the frame is masked: some pixel of its macropixel has its centre (x + 0.5, y + 0.5 in corner
// coordinates) inside the outline.
std::vector<bool> expectedMask(const std::vector<glm::dvec2> &outline, const PixelFormatInfo &format)
{
    const unsigned hs = format.encoding == ColourEncoding::Yuv && format.cbOffset != kNoComponent ? format.hSubSampling
                                                                                                  : 1,
                   vs = hs == 1 ? 1 : format.vSubSampling;
    std::vector<bool> inside(kWidth * kHeight), masked(kWidth * kHeight);
    for (unsigned y = 0; y < kHeight; ++y)
        for (unsigned x = 0; x < kWidth; ++x)
            inside[y * kWidth + x] = insideByAngles(outline, {x + 0.5, y + 0.5});
    for (unsigned y = 0; y < kHeight; ++y)
        for (unsigned x = 0; x < kWidth; ++x)
            for (unsigned my = y / vs * vs; my < std::min(kHeight, y / vs * vs + vs); ++my)
                for (unsigned mx = x / hs * hs; mx < std::min(kWidth, x / hs * hs + hs); ++mx)
                    if (inside[my * kWidth + mx])
                        masked[y * kWidth + x] = true;
    return masked;
}

TestFrame noiseFrame(const std::string &name)
{
    TestFrame frame = test::makeFrame(name, kWidth, kHeight, 8);
    std::mt19937 rng(7);
    for (unsigned p = 0; p < frame.layout.format->numPlanes; ++p)
        for (unsigned row = 0; row < frame.layout.format->planeHeight(p, kHeight); ++row)
            for (unsigned c = 0; c < frame.stride(p); ++c)
                if (test::byteKind(frame, p, c))
                    frame.plane(p)[size_t(row) * frame.stride(p) + c] = uint8_t(rng());
    return frame;
}

// Calls f(plane, offset, kind, first pixel) for every visible byte that carries a component (or padding: 'X').
template<typename F>
void forEachByte(const TestFrame &frame, F &&f, bool padding = false)
{
    for (unsigned p = 0; p < frame.layout.format->numPlanes; ++p)
        for (unsigned row = 0; row < frame.layout.format->planeHeight(p, kHeight); ++row)
            for (unsigned c = 0; c < frame.stride(p); ++c) {
                const char kind = test::byteKind(frame, p, c);
                const auto pixels = test::pixelsOfByte(frame, p, row, c);
                if (kind && (padding || kind != 'X') && !pixels.empty())
                    f(p, size_t(row) * frame.stride(p) + c, kind, pixels.front());
            }
}

// A screen mask in a top-left viewport: its points are the outline's pixel corners.
PrivacyMasks screenMask(const std::vector<glm::dvec2> &outline, std::optional<Rgba> fill, unsigned block,
                        const StreamFormat &format)
{
    MaskShape shape;
    for (const glm::dvec2 &p : outline)
        shape.points.push_back({p, 0.0});
    shape.fill = fill;
    shape.blockPx = block;
    OverlayScene scene;
    scene.annotations.push_back(test::annotation("mask", shape));
    PrivacyMasks masks(scene, format);
    const Camera camera = test::groundCamera(kWidth, kHeight);
    EXPECT_TRUE(masks.setCamera(camera, *SceneGraph::create({})));
    return masks;
}

class PrivacyMaskFormat : public testing::TestWithParam<std::string>
{};

TEST(PolygonSpans, CoverThePixelsWhoseCentresTheWindingNumberPutsInside)
{
    const std::vector<glm::dvec2> outline = starOutline();
    std::vector<RowSpan> spans;
    polygonSpans(outline, int(kWidth), int(kHeight), spans);
    const SpanRows rows(spans, kWidth, kHeight);
    unsigned inside = 0;
    for (unsigned y = 0; y < kHeight; ++y)
        for (unsigned x = 0; x < kWidth; ++x) {
            bool covered = false;
            for (const RowSpan &s : rows.row(y))
                covered |= int(x) >= s.x0 && int(x) < s.x1;
            const bool expected = insideByAngles(outline, {x + 0.5, y + 0.5});
            EXPECT_EQ(covered, expected) << x << "," << y;
            inside += expected;
        }
    EXPECT_EQ(rows.area(), inside);
    EXPECT_GT(inside, 300u); // the star's centre is filled too (nonzero rule): not a hollow pentagram
}

TEST(PolygonSpans, ClipsToTheFrameAndTakesFarPoints)
{
    const std::vector<glm::dvec2> outline{{-1e9, -1e9}, {1e9, -1e9}, {1e9, 1e9}, {-1e9, 1e9}};
    std::vector<RowSpan> spans;
    polygonSpans(outline, int(kWidth), int(kHeight), spans);
    EXPECT_EQ(SpanRows(spans, kWidth, kHeight).area(), uint64_t(kWidth) * kHeight);
}

TEST_P(PrivacyMaskFormat, FillTakesTheColourAndLeavesEveryOtherByte)
{
    const StreamFormat format = test::streamFormat(GetParam(), kWidth, kHeight);
    const Rgba colour{32, 160, 96, 255};
    TestFrame frame = noiseFrame(GetParam());
    const TestFrame original = frame;
    TestFrame painted = test::makeFrame(GetParam(), kWidth, kHeight, 8);
    test::fillRgb(painted, format.colorimetry, colour.r, colour.g, colour.b);
    PrivacyMasks masks = screenMask(starOutline(), colour, 16, format);
    masks.apply(frame.view());
    const std::vector<bool> masked = expectedMask(starOutline(), *format.format);
    unsigned touched = 0;
    forEachByte(
        frame,
        [&](unsigned p, size_t offset, char kind, cv::Point pixel) {
            const uint8_t got = frame.plane(p)[offset];
            if (!masked[pixel.y * kWidth + pixel.x]) {
                EXPECT_EQ(got, original.plane(p)[offset]) << kind << " at " << pixel;
                return;
            }
            ++touched;
            const uint8_t want = kind == 'A' || kind == 'X' ? 255 : painted.plane(p)[offset];
            EXPECT_NEAR(got, want, 1) << kind << " at " << pixel;
        },
        true);
    EXPECT_GT(touched, 300u);
    EXPECT_TRUE(frame.guardIntact());
}

// A concave outline reaching past the right and bottom edges (blocks cut by the frame, the last macropixel of an
// odd width and height) with a notch towards the middle.
std::vector<glm::dvec2> edgeOutline()
{
    return {{25.3, -4.0}, {70.0, -4.0}, {70.0, 60.0}, {-5.0, 60.0}, {-5.0, 38.6}, {31.7, 27.2}};
}

// Pixelates the noise frame and checks every byte, per pixel, against the block averages summed here from the bytes
// test_frames says belong to each block: the blocks are block x block pixels from the frame's origin (block rounded
// up to even where chroma is subsampled), and a block's mean is over its masked samples of that kind only.
void expectPixelated(const std::string &formatName, const std::vector<glm::dvec2> &outline, unsigned block)
{
    const StreamFormat format = test::streamFormat(formatName, kWidth, kHeight);
    const bool subsampled = format.format->encoding == ColourEncoding::Yuv && format.format->cbOffset != kNoComponent;
    const int side = int(std::max(2u, subsampled ? (block + 1) / 2 * 2 : block));
    TestFrame frame = noiseFrame(formatName);
    const TestFrame original = frame;
    PrivacyMasks masks = screenMask(outline, std::nullopt, block, format);
    masks.apply(frame.view());
    const std::vector<bool> masked = expectedMask(outline, *format.format);
    // Sums and counts per (kind, block), from the original bytes.
    std::map<std::tuple<char, int, int>, std::pair<unsigned, unsigned>> blocks;
    const auto blockOf = [&](char kind, cv::Point pixel) {
        return std::tuple(kind, pixel.x / side, pixel.y / side);
    };
    forEachByte(
        original,
        [&](unsigned p, size_t offset, char kind, cv::Point pixel) {
            if (masked[pixel.y * kWidth + pixel.x]) {
                auto &[sum, count] = blocks[blockOf(kind, pixel)];
                sum += original.plane(p)[offset], ++count;
            }
        },
        true);
    unsigned wrong = 0;
    forEachByte(
        frame,
        [&](unsigned p, size_t offset, char kind, cv::Point pixel) {
            const uint8_t got = frame.plane(p)[offset];
            if (!masked[pixel.y * kWidth + pixel.x]) {
                wrong += got != original.plane(p)[offset];
                EXPECT_EQ(got, original.plane(p)[offset]) << kind << " at " << pixel << ", block " << block;
                return;
            }
            const auto [sum, count] = blocks[blockOf(kind, pixel)];
            wrong += got != (sum + count / 2) / count;
            EXPECT_EQ(got, (sum + count / 2) / count) << kind << " at " << pixel << ", block " << block;
        },
        true);
    EXPECT_EQ(wrong, 0u) << "block " << block;
    EXPECT_GE(blocks.size(), 4u); // a 32 px block: 4 of them at least, of one kind
    EXPECT_TRUE(frame.guardIntact());
}

TEST_P(PrivacyMaskFormat, PixelationIsEachBlocksAverageOfItsMaskedSamples)
{
    expectPixelated(GetParam(), starOutline(), 8);
}

// Blocks of every size the benchmarks time and odd ones, over a mask that the frame's edges cut.
TEST_P(PrivacyMaskFormat, PixelationOfBlocksTheFrameEdgeCuts)
{
    for (unsigned block : {2u, 5u, 8u, 16u, 32u})
        for (const std::vector<glm::dvec2> &outline : {edgeOutline(), starOutline()})
            expectPixelated(GetParam(), outline, block);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, PrivacyMaskFormat, testing::ValuesIn(test::formatNames()), test::formatName);

// Screen points are pixel corners in the viewport's origin: [0, 0] .. [8, 4] is the 8 x 4 pixels at that origin.
TEST(PrivacyMasks, ScreenPointsArePixelCornersInTheViewportsOrigin)
{
    const StreamFormat format = test::streamFormat("RGB24", kWidth, kHeight);
    for (Origin origin : {Origin::TopLeft, Origin::BottomLeft}) {
        MaskShape shape;
        shape.points = {{0, 0, 0}, {8, 0, 0}, {8, 4, 0}, {0, 4, 0}};
        OverlayScene scene;
        scene.annotations.push_back(test::annotation("corner", shape));
        PrivacyMasks masks(scene, format);
        ASSERT_TRUE(masks.setCamera(test::groundCamera(kWidth, kHeight, origin), *SceneGraph::create({})));
        const SpanRows &rows = masks.spans(0);
        EXPECT_EQ(rows.area(), 32u);
        const unsigned firstRow = origin == Origin::TopLeft ? 0 : kHeight - 4;
        for (unsigned y = firstRow; y < firstRow + 4; ++y) {
            ASSERT_EQ(rows.row(y).size(), 1u) << y;
            EXPECT_EQ(rows.row(y)[0].x0, 0);
            EXPECT_EQ(rows.row(y)[0].x1, 8);
        }
    }
}

// A world mask is the polygon of its projected corners (cv-free: the camera's own point projection is tested
// against cv::projectPoints elsewhere); a corner behind the camera is clipped away, not folded onto the image.
TEST(PrivacyMasks, WorldMaskFollowsTheCameraAndClipsBehindIt)
{
    const StreamFormat format = test::streamFormat("RGB24", kWidth, kHeight);
    const Camera camera = test::groundCamera(kWidth, kHeight);
    MaskShape shape;
    shape.world = true;
    shape.points = {{0.5, -0.5, 0}, {1.5, -0.5, 0}, {1.5, 0.5, 0}, {0.5, 0.5, 0}};
    OverlayScene scene;
    scene.annotations.push_back(test::annotation("ground", shape));
    PrivacyMasks masks(scene, format);
    ASSERT_TRUE(masks.setCamera(camera, *SceneGraph::create({})));
    std::vector<glm::dvec2> outline;
    for (const glm::dvec3 &p : shape.points)
        outline.push_back(camera.project(p).pixel + glm::dvec2(0.5));
    unsigned expected = 0;
    for (unsigned y = 0; y < kHeight; ++y)
        for (unsigned x = 0; x < kWidth; ++x) {
            const bool inside = insideByAngles(outline, {x + 0.5, y + 0.5});
            expected += inside;
            bool covered = false;
            for (const RowSpan &s : masks.spans(0).row(y))
                covered |= int(x) >= s.x0 && int(x) < s.x1;
            EXPECT_EQ(covered, inside) << x << "," << y;
        }
    EXPECT_GT(expected, 20u);

    // The ground from 6 m in front of the camera to 10 m behind it: only the part in front shows, below the far
    // edge's row (a corner behind the camera divided by its negative w would land above it, mirrored).
    MaskShape behind;
    behind.world = true;
    behind.points = {{2, -1, 0}, {-14, -1, 0}, {-14, 1, 0}, {2, 1, 0}};
    OverlayScene second;
    second.annotations.push_back(test::annotation("behind", behind));
    PrivacyMasks clipped(second, format);
    ASSERT_TRUE(clipped.setCamera(camera, *SceneGraph::create({})));
    const ProjectedPoint farEdge = camera.project(glm::dvec3(2, 0, 0));
    ASSERT_EQ(farEdge.status, PointStatus::Visible);
    for (const RowSpan &s : clipped.spans(0).spans())
        EXPECT_GE(s.y, std::floor(farEdge.pixel.y)) << "a masked row above the far edge: a corner came back mirrored";
    EXPECT_EQ(clipped.spans(0).row(kHeight - 1).size(), 1u); // down to the bottom of the frame
    EXPECT_GT(clipped.spans(0).area(), 100u);
}

TEST(PrivacyMasks, ALayerHoldingAMaskCannotBeHidden)
{
    const StreamFormat format = test::streamFormat("YUYV", kWidth, kHeight);
    MaskShape shape;
    shape.points = {{0, 0, 0}, {8, 0, 0}, {8, 4, 0}};
    OverlayScene scene;
    scene.annotations.push_back(test::annotation("street", shape, kWhite, 2.0, "private"));
    scene.annotations.push_back(test::annotation("grid", GridShape{}, kWhite, 2.0, "grid"));
    auto renderer = test::makeRenderer(scene, test::groundCamera(kWidth, kHeight), format);
    const Status hidden = renderer->setLayerEnabled("private", false);
    ASSERT_FALSE(hidden);
    EXPECT_NE(hidden.error().message.find("privacy mask \"street\""), std::string::npos);
    EXPECT_TRUE(renderer->setLayerEnabled("private", true));
    EXPECT_TRUE(renderer->setLayerEnabled("grid", false));
}

} // namespace
} // namespace overlayd
