// SPDX-License-Identifier: Apache-2.0
// Colour accuracy of the native blend in every format, read back through OpenCV's converters.
//
// OpenCV's cvtColor YUV2BGR_* (YUYV, UYVY, YVYU, NV12, NV21, I420, YV12) implements BT.601 limited range
// (R = 1.164 (Y - 16) + 1.596 (Cr - 128), ...) in fixed point, so these tests use that colorimetry. One code of
// rounding in Y, Cb and Cr moves a channel by up to about 2 after conversion: the tolerance is kYuvTolerance.
// RGB formats are compared exactly; GREY by its luma code.
#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "overlay/blend/native_layer.h"
#include "test_frames.h"

namespace overlayd {
namespace {

using test::TestFrame;

constexpr int kYuvTolerance = 3;

struct Case {
    std::string format;
    unsigned width, height, stridePadding;
};

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

std::vector<Case> allCases()
{
    std::vector<Case> cases;
    for (const PixelFormatInfo &info : pixelFormats()) {
        for (const Case &size : {Case{"", 64, 48, 0}, Case{"", 64, 48, 32}, Case{"", 37, 29, 6}})
            cases.push_back({std::string(info.name), size.width, size.height, size.stridePadding});
    }
    return cases;
}

struct Swatch {
    Rgba colour;
    cv::Rect rect;
};

// Blocks at alternately odd and even x (so some edges split macropixels) and 2-pixel-wide vertical lines.
std::vector<Swatch> swatches()
{
    const Rgba colours[] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}, {0, 0, 0, 255}};
    std::vector<Swatch> result;
    for (int i = 0; i < 5; ++i) {
        result.push_back({colours[i], cv::Rect(1 + 7 * i, 3, 6, 6)});
        result.push_back({colours[i], cv::Rect(2 + 8 * i, 14, 2, 12)});
    }
    return result;
}

// A pixel whose whole 2x2 macropixel lies inside the swatch: blocks start at any x, lines at even x.
cv::Point centre(const cv::Rect &rect)
{
    return rect.width == 6 ? rect.tl() + cv::Point(3, 3) : rect.tl() + cv::Point(0, 6);
}

double luma601Code(const Rgba &c)
{
    return 16 + 219.0 / 255 * (0.299 * c.r + 0.587 * c.g + 0.114 * c.b);
}

class BlendColour : public testing::TestWithParam<Case>
{};

TEST_P(BlendColour, OpaqueSwatchesOverMidGrey)
{
    const Case &c = GetParam();
    TestFrame frame = test::makeFrame(c.format, c.width, c.height, c.stridePadding);
    const Colorimetry colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited};
    test::fillRgb(frame, colorimetry, 128, 128, 128);

    OverlayLayer layer(c.width, c.height);
    for (const Swatch &s : swatches())
        layer.fillRect(s.rect.x, s.rect.y, s.rect.width, s.rect.height, s.colour);
    layer.updateSpans();
    auto native = NativeLayer::convert(layer, test::format(c.format), colorimetry);
    ASSERT_TRUE(native);
    ASSERT_TRUE(native->blend(frame.view()));
    ASSERT_TRUE(frame.guardIntact());

    if (c.format == "GREY") {
        for (const Swatch &s : swatches()) {
            const cv::Point p = centre(s.rect);
            EXPECT_NEAR(frame.plane(0)[p.y * frame.stride(0) + p.x], luma601Code(s.colour), 1.0) << p;
        }
        return;
    }
    const cv::Mat bgr = test::toBgr(frame);
    const int tolerance = test::format(c.format).encoding == ColourEncoding::Rgb ? 0 : kYuvTolerance;
    for (const Swatch &s : swatches()) {
        const cv::Point p = centre(s.rect);
        const cv::Vec3b got = bgr.at<cv::Vec3b>(p);
        EXPECT_NEAR(got[2], s.colour.r, tolerance) << "R at " << p;
        EXPECT_NEAR(got[1], s.colour.g, tolerance) << "G at " << p;
        EXPECT_NEAR(got[0], s.colour.b, tolerance) << "B at " << p;
    }
    // Far from every swatch the grey is what it was.
    const cv::Vec3b grey = bgr.at<cv::Vec3b>(c.height - 1, c.width - 1);
    EXPECT_NEAR(grey[1], 128, kYuvTolerance);
}

// 50% white over black: every sample of the covered macropixels lands within one code of the exact value.
TEST_P(BlendColour, HalfAlphaWhiteOverBlack)
{
    const Case &c = GetParam();
    TestFrame frame = test::makeFrame(c.format, c.width, c.height, c.stridePadding);
    const Colorimetry colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited};
    test::fillRgb(frame, colorimetry, 0, 0, 0);
    OverlayLayer layer(c.width, c.height);
    const cv::Rect rect(4, 4, 8, 8);
    layer.fillRect(rect.x, rect.y, rect.width, rect.height, {255, 255, 255, 128});
    layer.updateSpans();
    auto native = NativeLayer::convert(layer, test::format(c.format), colorimetry);
    ASSERT_TRUE(native);
    ASSERT_TRUE(native->blend(frame.view()));

    const double a = 128.0 / 255;
    for (unsigned p = 0; p < test::format(c.format).numPlanes; ++p) {
        for (unsigned row = 0; row < test::format(c.format).planeHeight(p, c.height); ++row) {
            for (unsigned col = 0; col < frame.stride(p); ++col) {
                const std::vector<cv::Point> pixels = test::pixelsOfByte(frame, p, row, col);
                const bool inside = !pixels.empty() && std::all_of(pixels.begin(), pixels.end(),
                                                                   [&](cv::Point q) { return rect.contains(q); });
                if (!inside)
                    continue;
                const char kind = test::byteKind(frame, p, col);
                const double black = kind == 'Y' ? 16 : (kind == 'U' || kind == 'V') ? 128 : kind == 'A' ? 255 : 0;
                const double white = kind == 'Y' ? 235 : (kind == 'U' || kind == 'V') ? 128 : 255;
                const double expected = kind == 'X' ? 0x77 : white * a + black * (1 - a);
                EXPECT_NEAR(frame.plane(p)[row * frame.stride(p) + col], expected, 1.0)
                    << "plane " << p << " row " << row << " byte " << col << " (" << kind << ")";
            }
        }
    }
}

// Chroma-aware: a macropixel's chroma moves by its covered fraction towards the overlay's chroma.
TEST(BlendChroma, PartlyCoveredMacropixelIsCoverageWeighted)
{
    const Colorimetry colorimetry{YcbcrMatrix::Bt601, ColourRange::Limited};
    const double redCb = 128 - 112 * 0.299 / 0.886, redCr = 240; // BT.601 limited red; grey is 128, 128
    struct Probe {
        const char *format;
        unsigned width, plane, cbByte, crByte; // chroma of the macropixel holding the red pixel
        int x;
        double weight;
    };
    const Probe probes[] = {
        {"YUYV", 8, 0, 1, 3, 0, 0.5},  // 2x1: one of two pixels
        {"UYVY", 8, 0, 4, 6, 3, 0.5},  // second pixel of the second group
        {"NV12", 8, 1, 0, 1, 1, 0.25}, // 2x2: one of four pixels
        {"NV16", 8, 1, 2, 3, 2, 0.5},
        {"YUYV", 5, 0, 9, 11, 4, 1.0}, // odd width: the last group holds one pixel, fully covered
    };
    for (const Probe &probe : probes) {
        TestFrame frame = test::makeFrame(probe.format, probe.width, 4, 0);
        test::fillRgb(frame, colorimetry, 128, 128, 128);
        OverlayLayer layer(probe.width, 4);
        layer.fillRect(probe.x, 0, 1, 1, {255, 0, 0, 255});
        layer.updateSpans();
        auto native = NativeLayer::convert(layer, test::format(probe.format), colorimetry);
        ASSERT_TRUE(native);
        ASSERT_TRUE(native->blend(frame.view()));
        const uint8_t *chroma = frame.plane(probe.plane);
        EXPECT_NEAR(chroma[probe.cbByte], probe.weight * redCb + (1 - probe.weight) * 128, 1.0) << probe.format;
        EXPECT_NEAR(chroma[probe.crByte], probe.weight * redCr + (1 - probe.weight) * 128, 1.0) << probe.format;
    }
}

// BT.709 limited and BT.601 full range, against the published code values of red (BT.709-6: Y 63, Cb 102, Cr 240;
// JPEG/JFIF BT.601 full: Y 76, Cb 85, Cr 255) and, for full range, OpenCV's YCrCb2BGR (BT.601 full range).
TEST(BlendChroma, OtherColorimetries)
{
    struct Expect {
        Colorimetry colorimetry;
        double y, cb, cr;
    };
    const Expect expected[] = {{{YcbcrMatrix::Bt709, ColourRange::Limited}, 62.56, 102.34, 240},
                               {{YcbcrMatrix::Bt601, ColourRange::Full}, 76.25, 85.0, 255}};
    for (const Expect &e : expected) {
        TestFrame frame = test::makeFrame("NV12", 4, 4, 0);
        test::fillRgb(frame, e.colorimetry, 128, 128, 128);
        OverlayLayer layer(4, 4);
        layer.fillRect(0, 0, 2, 2, {255, 0, 0, 255});
        layer.updateSpans();
        auto native = NativeLayer::convert(layer, test::format("NV12"), e.colorimetry);
        ASSERT_TRUE(native);
        ASSERT_TRUE(native->blend(frame.view()));
        EXPECT_NEAR(frame.plane(0)[0], e.y, 1.0);
        EXPECT_NEAR(frame.plane(1)[0], e.cb, 1.0);
        EXPECT_NEAR(frame.plane(1)[1], e.cr, 1.0);
        if (e.colorimetry.range == ColourRange::Full) {
            cv::Mat ycrcb(1, 1, CV_8UC3, cv::Scalar(frame.plane(0)[0], frame.plane(1)[1], frame.plane(1)[0])), bgr;
            cv::cvtColor(ycrcb, bgr, cv::COLOR_YCrCb2BGR);
            const cv::Vec3b got = bgr.at<cv::Vec3b>(0, 0);
            EXPECT_NEAR(got[2], 255, 2);
            EXPECT_NEAR(got[1], 0, 2);
            EXPECT_NEAR(got[0], 0, 2);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, BlendColour, testing::ValuesIn(allCases()), caseName);

} // namespace
} // namespace overlayd
