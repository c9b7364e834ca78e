// SPDX-License-Identifier: Apache-2.0
// Test frames of a pattern with saturated bars (the colours where matrices and ranges differ most) above smooth
// gradients (where JPEG's quantisation error stays small), compared through OpenCV's JPEG decoder.
#include "jpeg_test_frames.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include <turbojpeg.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "media/convert/frame_convert.h"

namespace overlayd::test {

namespace {

constexpr uint8_t kBars[8][3] = {{255, 255, 255}, {255, 255, 0}, {0, 255, 255}, {0, 255, 0},
                                 {255, 0, 255},   {255, 0, 0},   {0, 0, 255},   {0, 0, 0}};

// Bars and the bars/gradient boundary sit on 16-pixel lines, so that no chroma site or JPEG block mixes two bars:
// what remains at their edges is the decoder's smooth chroma upsampling, which frameToRgb does not do.
struct Layout {
    unsigned barWidth, barsHeight;
};

Layout patternLayout(unsigned width, unsigned height)
{
    return {std::max(16u, width / 8 / 16 * 16), std::max(16u, height / 2 / 16 * 16)};
}

RgbImage pattern(unsigned width, unsigned height)
{
    const Layout layout = patternLayout(width, height);
    RgbImage image = RgbImage::allocate(width, height);
    for (unsigned y = 0; y < height; ++y) {
        uint8_t *px = image.row(y);
        for (unsigned x = 0; x < width; ++x, px += 3) {
            if (y < layout.barsHeight) {
                const uint8_t *bar = kBars[std::min(7u, x / layout.barWidth)];
                px[0] = bar[0], px[1] = bar[1], px[2] = bar[2];
                continue;
            }
            px[0] = uint8_t(255 * x / width);
            px[1] = uint8_t(255 * (y - layout.barsHeight) / (height - layout.barsHeight));
            px[2] = uint8_t(255 - 255 * x / width / 2);
        }
    }
    return image;
}

cv::Mat asMat(const RgbImage &image)
{
    return cv::Mat(int(image.height), int(image.width), CV_8UC3, const_cast<uint8_t *>(image.rgb.data()));
}

} // namespace

FrameBuffer patternFrame(const std::string &formatName, unsigned width, unsigned height, Colorimetry colorimetry,
                         unsigned stridePadding)
{
    const PixelFormatInfo *format = pixelFormatFromName(formatName);
    if (!format)
        throw std::runtime_error("no pixel format " + formatName);
    const unsigned stride = stridePadding ? format->minStride(0, width) + stridePadding : 0;
    auto frame = FrameBuffer::allocate({format, width, height, stride, colorimetry, 30.0});
    if (!frame)
        throw std::runtime_error(frame.error().message);
    if (auto drawn = rgbToFrame(pattern(width, height), colorimetry, frame->view()); !drawn)
        throw std::runtime_error(drawn.error().message);
    return std::move(*frame);
}

JpegHeader readHeader(const std::vector<uint8_t> &jpeg)
{
    JpegHeader header;
    tjhandle handle = tjInitDecompress();
    int colorspace = 0;
    if (tjDecompressHeader3(handle, jpeg.data(), jpeg.size(), &header.width, &header.height, &header.subsampling,
                            &colorspace) != 0)
        header = {};
    tjDestroy(handle);
    return header;
}

namespace {

// The JPEG as OpenCV decodes it and frameToRgb's image of the frame, both R G B; empty when either fails or the
// sizes differ.
std::pair<cv::Mat, cv::Mat> decodedAndReference(const std::vector<uint8_t> &jpeg, const FrameView &frame,
                                                Colorimetry colorimetry)
{
    const cv::Mat bgr =
        cv::imdecode(cv::Mat(1, int(jpeg.size()), CV_8UC1, const_cast<uint8_t *>(jpeg.data())), cv::IMREAD_COLOR);
    auto reference = frameToRgb(frame, colorimetry);
    if (bgr.empty() || !reference || bgr.cols != int(frame.width) || bgr.rows != int(frame.height))
        return {};
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    return {rgb, asMat(*reference).clone()};
}

} // namespace

std::array<double, 3> meanError(const std::vector<uint8_t> &jpeg, const FrameView &frame, Colorimetry colorimetry)
{
    const auto [decoded, reference] = decodedAndReference(jpeg, frame, colorimetry);
    if (decoded.empty())
        return {255.0, 255.0, 255.0};
    cv::Mat difference;
    cv::absdiff(decoded, reference, difference);
    const cv::Scalar mean = cv::mean(difference);
    return {mean[0], mean[1], mean[2]};
}

int worstBarError(const std::vector<uint8_t> &jpeg, const FrameView &frame, Colorimetry colorimetry)
{
    const auto [decoded, reference] = decodedAndReference(jpeg, frame, colorimetry);
    if (decoded.empty())
        return 255;
    const Layout layout = patternLayout(frame.width, frame.height);
    int worst = 0;
    for (unsigned bar = 0; bar < 8; ++bar) {
        const unsigned x = std::min(bar * layout.barWidth + layout.barWidth / 2, frame.width - 1);
        const cv::Vec3b a = decoded.at<cv::Vec3b>(int(layout.barsHeight / 2), int(x));
        const cv::Vec3b b = reference.at<cv::Vec3b>(int(layout.barsHeight / 2), int(x));
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(a[c]) - int(b[c])));
    }
    return worst;
}

double worstChannel(const std::array<double, 3> &error)
{
    return std::max({error[0], error[1], error[2]});
}

} // namespace overlayd::test
