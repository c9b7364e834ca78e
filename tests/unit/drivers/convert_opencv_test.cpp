// SPDX-License-Identifier: Apache-2.0
// The whole-frame converter against OpenCV's cvtColor, which implements BT.601 limited range for its YUV formats
// (YUYV, UYVY, YVYU, NV12, NV21, I420, YV12) and exact channel shuffles for RGB/BGR; GREY is compared with
// RGB2GRAY (full-range BT.601 luma). Decoding reads the frame's own memory through OpenCV; encoding is compared with
// OpenCV's I420 planes, read back from our frames with byte positions written out here by hand.
#include <ostream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "media/convert/frame_convert.h"
#include "media/convert/packing.h"
#include "test_util.h"

namespace overlayd {
namespace {

using test::makeFrame;

constexpr Colorimetry kBt601Limited{};
constexpr Colorimetry kBt601Full{YcbcrMatrix::Bt601, ColourRange::Full};

struct YuvCase {
    const char *format;
    int toRgb; // OpenCV's decoding code
};

constexpr YuvCase kYuvCases[] = {
    {"YUYV", cv::COLOR_YUV2RGB_YUYV},   {"UYVY", cv::COLOR_YUV2RGB_UYVY}, {"YVYU", cv::COLOR_YUV2RGB_YVYU},
    {"NV12", cv::COLOR_YUV2RGB_NV12},   {"NV21", cv::COLOR_YUV2RGB_NV21}, {"YUV420", cv::COLOR_YUV2RGB_I420},
    {"YVU420", cv::COLOR_YUV2RGB_YV12},
};

// Keeps gtest from printing the case's raw bytes.
void PrintTo(const YuvCase &c, std::ostream *os)
{
    *os << c.format;
}

// The frame's memory as OpenCV expects it: packed 4:2:2 as 2-channel rows with the frame's stride, 4:2:0 as one
// contiguous (3H/2) x W plane (these frames are packed, so the planes follow each other).
cv::Mat openCvView(FrameBuffer &frame)
{
    const FrameView view = frame.view();
    if (view.format->numPlanes == 1)
        return cv::Mat(int(view.height), int(view.width), CV_8UC2, view.planes[0].data, view.planes[0].stride);
    return cv::Mat(int(view.height * 3 / 2), int(view.width), CV_8UC1, frame.data());
}

// Random but valid code values: Y in 16..235, Cb/Cr in 16..240.
YcbcrImage randomSamples(const PixelFormatInfo &format, unsigned width, unsigned height)
{
    YcbcrImage image = ycbcrImageFor(format, width, height);
    cv::RNG random(42);
    for (uint8_t &y : image.y)
        y = uint8_t(random.uniform(16, 236));
    for (size_t i = 0; i < image.cb.size(); ++i)
        image.cb[i] = uint8_t(random.uniform(16, 241)), image.cr[i] = uint8_t(random.uniform(16, 241));
    return image;
}

int maxDifference(const cv::Mat &a, const cv::Mat &b)
{
    cv::Mat difference;
    cv::absdiff(a, b, difference);
    double worst = 0;
    cv::minMaxLoc(difference.reshape(1), nullptr, &worst);
    return int(worst);
}

class YuvDecode : public testing::TestWithParam<YuvCase>
{};

TEST_P(YuvDecode, FrameToRgbMatchesOpenCv)
{
    // OpenCV reads 4:2:0 frames as one contiguous block: only packed 4:2:2 gets stride padding.
    const unsigned padding = test::format(GetParam().format).numPlanes == 1 ? 12 : 0;
    FrameBuffer frame = makeFrame(GetParam().format, 64, 48, padding);
    ASSERT_TRUE(packYcbcr(randomSamples(*frame.layout().format, 64, 48), frame.view()));
    auto ours = frameToRgb(frame.view(), kBt601Limited);
    ASSERT_TRUE(ours);
    cv::Mat reference;
    cv::cvtColor(openCvView(frame), reference, GetParam().toRgb);
    EXPECT_LE(maxDifference(test::toMat(*ours), reference), 2);
}

INSTANTIATE_TEST_SUITE_P(OpenCv, YuvDecode, testing::ValuesIn(kYuvCases),
                         [](const auto &test) { return std::string(test.param.format); });

// OpenCV's I420 encoding of an image whose 2x2 macropixels are uniform (so chroma averaging cannot differ).
struct I420Reference {
    cv::Mat y, u, v; // W x H, W/2 x H/2, W/2 x H/2
};

I420Reference openCvI420(const RgbImage &image)
{
    cv::Mat i420;
    cv::cvtColor(test::toMat(image), i420, cv::COLOR_RGB2YUV_I420);
    const int w = int(image.width), h = int(image.height);
    I420Reference ref;
    ref.y = i420.rowRange(0, h).clone();
    ref.u = cv::Mat(h / 2, w / 2, CV_8UC1, i420.ptr(h)).clone();
    ref.v = cv::Mat(h / 2, w / 2, CV_8UC1, i420.ptr(h) + size_t(w / 2) * (h / 2)).clone();
    return ref;
}

// Byte positions of Y, Cb and Cr of pixel (x, y), per format, written out from the V4L2 documentation.
struct Sampler {
    FrameView view;
    uint8_t at(unsigned plane, size_t row, size_t column) const
    {
        return view.planes[plane].data[row * view.planes[plane].stride + column];
    }
    uint8_t y(const std::string &name, unsigned x, unsigned row) const
    {
        if (name == "YUYV" || name == "YVYU")
            return at(0, row, 2 * x);
        if (name == "UYVY")
            return at(0, row, 2 * x + 1);
        return at(0, row, x);
    }
    uint8_t chroma(const std::string &name, bool cb, unsigned x, unsigned row) const
    {
        const size_t g = x / 2;
        if (name == "YUYV")
            return at(0, row, 4 * g + (cb ? 1 : 3));
        if (name == "UYVY")
            return at(0, row, 4 * g + (cb ? 0 : 2));
        if (name == "YVYU")
            return at(0, row, 4 * g + (cb ? 3 : 1));
        if (name == "NV12")
            return at(1, row / 2, 2 * g + (cb ? 0 : 1));
        if (name == "NV21")
            return at(1, row / 2, 2 * g + (cb ? 1 : 0));
        if (name == "NV16")
            return at(1, row, 2 * g + (cb ? 0 : 1));
        if (name == "YUV420")
            return at(cb ? 1 : 2, row / 2, g);
        return at(cb ? 2 : 1, row / 2, g); // YVU420
    }
};

class YuvEncode : public testing::TestWithParam<const char *>
{};

TEST_P(YuvEncode, RgbToFrameMatchesOpenCvI420)
{
    const std::string name = GetParam();
    const RgbImage image = test::blockyImage(64, 48, 2, 2, 7);
    FrameBuffer frame = makeFrame(name, 64, 48, 10);
    ASSERT_TRUE(rgbToFrame(image, kBt601Limited, frame.view()));
    const I420Reference ref = openCvI420(image);
    const Sampler sampler{frame.view()};
    int worst = 0;
    for (unsigned y = 0; y < 48; ++y) {
        for (unsigned x = 0; x < 64; ++x) {
            worst = std::max(worst, std::abs(int(sampler.y(name, x, y)) - ref.y.at<uint8_t>(int(y), int(x))));
            const int u = ref.u.at<uint8_t>(int(y / 2), int(x / 2)), v = ref.v.at<uint8_t>(int(y / 2), int(x / 2));
            worst = std::max(worst, std::abs(int(sampler.chroma(name, true, x, y)) - u));
            worst = std::max(worst, std::abs(int(sampler.chroma(name, false, x, y)) - v));
        }
    }
    EXPECT_LE(worst, 1);
}

INSTANTIATE_TEST_SUITE_P(OpenCv, YuvEncode,
                         testing::Values("YUYV", "UYVY", "YVYU", "NV12", "NV21", "NV16", "YUV420", "YVU420"));

struct RgbCase {
    const char *format;
    int fromRgb;  // OpenCV's shuffle from R G B to the format's byte order
    int channels; // bytes per pixel
};

TEST(RgbFormats, MatchOpenCvChannelOrder)
{
    const RgbImage image = test::blockyImage(33, 17, 1, 1, 3);
    for (const RgbCase c : {RgbCase{"RGB24", -1, 3}, RgbCase{"BGR24", cv::COLOR_RGB2BGR, 3},
                            RgbCase{"RGBA32", cv::COLOR_RGB2RGBA, 4}, RgbCase{"BGRA32", -2, 4}}) {
        SCOPED_TRACE(c.format);
        FrameBuffer frame = makeFrame(c.format, 33, 17, 8);
        ASSERT_TRUE(rgbToFrame(image, kBt601Limited, frame.view()));
        cv::Mat expected;
        if (c.fromRgb == -1)
            expected = test::toMat(image).clone();
        else if (c.fromRgb == -2) { // BGRA32 is A B G R in memory (V4L2), i.e. OpenCV's RGBA reversed
            cv::Mat rgba;
            cv::cvtColor(test::toMat(image), rgba, cv::COLOR_RGB2RGBA);
            cv::Mat channels[4];
            cv::split(rgba, channels);
            cv::merge(std::vector<cv::Mat>{channels[3], channels[2], channels[1], channels[0]}, expected);
        } else
            cv::cvtColor(test::toMat(image), expected, c.fromRgb);
        const FrameView view = frame.view();
        const cv::Mat ours(17, 33, CV_8UC(c.channels), view.planes[0].data, view.planes[0].stride);
        EXPECT_EQ(maxDifference(ours, expected), 0);
        auto back = frameToRgb(view, kBt601Limited);
        ASSERT_TRUE(back);
        EXPECT_EQ(back->rgb, image.rgb);
    }
}

TEST(GreyFormat, FullRangeLumaMatchesOpenCvGray)
{
    const RgbImage image = test::blockyImage(40, 30, 1, 1, 5);
    FrameBuffer frame = makeFrame("GREY", 40, 30, 3);
    ASSERT_TRUE(rgbToFrame(image, kBt601Full, frame.view()));
    cv::Mat gray;
    cv::cvtColor(test::toMat(image), gray, cv::COLOR_RGB2GRAY);
    const FrameView view = frame.view();
    EXPECT_LE(maxDifference(cv::Mat(30, 40, CV_8UC1, view.planes[0].data, view.planes[0].stride), gray), 1);
}

// OpenCV's RGB2YCrCb is full-range BT.601 at 4:4:4: the same as our RGB -> 4:4:4 encoding in bt601-full.
TEST(FullRange, RgbToYcbcr444MatchesOpenCvYCrCb)
{
    const RgbImage image = test::blockyImage(40, 30, 1, 1, 9);
    FrameBuffer frame = makeFrame("RGB24", 40, 30);
    ASSERT_TRUE(rgbToFrame(image, kBt601Full, frame.view()));
    auto samples = frameToYcbcr(frame.view(), kBt601Full);
    ASSERT_TRUE(samples);
    cv::Mat ycrcb;
    cv::cvtColor(test::toMat(image), ycrcb, cv::COLOR_RGB2YCrCb);
    int worst = 0;
    for (int y = 0; y < 30; ++y) {
        for (int x = 0; x < 40; ++x) {
            const cv::Vec3b ref = ycrcb.at<cv::Vec3b>(y, x);
            const size_t i = size_t(y) * 40 + x;
            worst = std::max({worst, std::abs(samples->y[i] - ref[0]), std::abs(samples->cr[i] - ref[1]),
                              std::abs(samples->cb[i] - ref[2])});
        }
    }
    EXPECT_LE(worst, 1);
}

// The per-frame form (the Y4M sink's) gives the same samples and, frame after frame of one size, keeps its buffers:
// no allocation, so no page faults per frame.
TEST(PerFrameConversion, ReusesItsBuffersAndMatchesTheAllocatingForm)
{
    for (const char *name : {"RGB24", "YUYV", "NV12"}) {
        SCOPED_TRACE(name);
        const RgbImage image = test::blockyImage(40, 30, 2, 2, 5);
        FrameBuffer frame = makeFrame(name, 40, 30);
        ASSERT_TRUE(rgbToFrame(image, kBt601Full, frame.view()));
        YcbcrImage out;
        RgbImage scratch;
        ASSERT_TRUE(frameToYcbcr(frame.view(), kBt601Full, out, scratch));
        const uint8_t *y = out.y.data(), *cb = out.cb.data(), *rgb = scratch.rgb.data();
        ASSERT_TRUE(frameToYcbcr(frame.view(), kBt601Full, out, scratch));
        EXPECT_EQ(out.y.data(), y);
        EXPECT_EQ(out.cb.data(), cb);
        EXPECT_EQ(scratch.rgb.data(), rgb);
        const auto fresh = frameToYcbcr(frame.view(), kBt601Full);
        ASSERT_TRUE(fresh);
        EXPECT_EQ(out.y, fresh->y);
        EXPECT_EQ(out.cb, fresh->cb);
        EXPECT_EQ(out.cr, fresh->cr);
        EXPECT_EQ(out.hSub, fresh->hSub);
        EXPECT_EQ(out.vSub, fresh->vSub);
    }
}

} // namespace
} // namespace overlayd
