// SPDX-License-Identifier: Apache-2.0
// Whole-frame conversion: the encoding (RGB or Y'CbCr) picks the path, the table entry drives the packing.
#include "media/convert/frame_convert.h"

#include <algorithm>

#include "media/convert/colour_convert.h"
#include "media/convert/packing.h"

namespace overlayd {

namespace {

bool hasChroma(const PixelFormatInfo &format)
{
    return format.cbOffset != kNoComponent;
}

} // namespace

Status rgbToFrame(const RgbImage &image, Colorimetry colorimetry, const FrameView &frame)
{
    if (!frame.format)
        return makeError(ErrorCode::InvalidArgument, "frame has no pixel format");
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding == ColourEncoding::Rgb)
        return packRgb(image, frame);
    return packYcbcr(rgbToYcbcr(image, colorimetry, format.hSubSampling, format.vSubSampling, hasChroma(format)),
                     frame);
}

Result<RgbImage> frameToRgb(const FrameView &frame, Colorimetry colorimetry)
{
    if (!frame.format)
        return makeError(ErrorCode::InvalidArgument, "frame has no pixel format");
    if (frame.format->encoding == ColourEncoding::Rgb)
        return unpackRgb(frame);
    auto samples = unpackYcbcr(frame);
    if (!samples)
        return samples.error();
    return ycbcrToRgb(*samples, colorimetry);
}

Status ycbcrToFrame(const YcbcrImage &image, Colorimetry colorimetry, const FrameView &frame)
{
    if (!frame.format)
        return makeError(ErrorCode::InvalidArgument, "frame has no pixel format");
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding == ColourEncoding::Rgb)
        return packRgb(ycbcrToRgb(image, colorimetry), frame);
    if (!hasChroma(format) || (image.hSub == format.hSubSampling && image.vSub == format.vSubSampling))
        return packYcbcr(image, frame);
    if (!image.hasChroma) {
        // Luma-only into a colour format: neutral chroma.
        YcbcrImage grey =
            YcbcrImage::allocate(image.width, image.height, format.hSubSampling, format.vSubSampling, true);
        grey.y = image.y;
        std::fill(grey.cb.begin(), grey.cb.end(), uint8_t(128));
        std::fill(grey.cr.begin(), grey.cr.end(), uint8_t(128));
        return packYcbcr(grey, frame);
    }
    return packYcbcr(resampleChroma(image, format.hSubSampling, format.vSubSampling), frame);
}

Status frameToYcbcr(const FrameView &frame, Colorimetry colorimetry, YcbcrImage &out, RgbImage &rgbScratch)
{
    if (!frame.format)
        return makeError(ErrorCode::InvalidArgument, "frame has no pixel format");
    if (frame.format->encoding == ColourEncoding::Yuv)
        return unpackYcbcr(frame, out);
    if (auto unpacked = unpackRgb(frame, rgbScratch); !unpacked)
        return unpacked;
    rgbToYcbcr(rgbScratch, colorimetry, 1, 1, true, out);
    return Ok{};
}

Result<YcbcrImage> frameToYcbcr(const FrameView &frame, Colorimetry colorimetry)
{
    YcbcrImage out;
    RgbImage rgb;
    if (auto converted = frameToYcbcr(frame, colorimetry, out, rgb); !converted)
        return converted.error();
    return out;
}

Status fillFrame(const FrameView &frame, Colorimetry colorimetry, uint8_t r, uint8_t g, uint8_t b)
{
    RgbImage image = RgbImage::allocate(frame.width, frame.height);
    for (size_t i = 0; i < image.rgb.size(); i += 3)
        image.rgb[i] = r, image.rgb[i + 1] = g, image.rgb[i + 2] = b;
    return rgbToFrame(image, colorimetry, frame);
}

} // namespace overlayd
