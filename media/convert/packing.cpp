// SPDX-License-Identifier: Apache-2.0
// Table-driven packing. Luma of pixel x sits at (x / pixelsPerGroup) * bytesPerGroup + yOffset[x % pixelsPerGroup]
// of plane 0; chroma sample c at c * step + offset of its plane, step being the plane's bytes per chroma sample
// pair (4 for packed 4:2:2, 2 for semi-planar, 1 for planar). This covers every YUV entry of the table.
#include "media/convert/packing.h"

#include <string>

namespace overlayd {

namespace {

bool sameSize(const YcbcrImage &image, const FrameView &frame)
{
    return image.width == frame.width && image.height == frame.height;
}

Status wrongKind(const FrameView &frame, const char *what)
{
    return makeError(ErrorCode::InvalidArgument, std::string(frame.format->name) + " is not " + what);
}

unsigned chromaStep(const PixelFormatInfo &format, unsigned plane)
{
    return format.planes[plane].bytesPerGroup * format.hSubSampling / format.pixelsPerGroup;
}

void packLumaRow(const PixelFormatInfo &format, const uint8_t *src, unsigned width, uint8_t *dst)
{
    const unsigned ppg = format.pixelsPerGroup, bpg = format.planes[0].bytesPerGroup;
    for (unsigned x = 0; x < width; dst += bpg) {
        for (unsigned k = 0; k < ppg && x < width; ++k, ++x)
            dst[format.yOffset[k]] = src[x];
    }
}

void unpackLumaRow(const PixelFormatInfo &format, const uint8_t *src, unsigned width, uint8_t *dst)
{
    const unsigned ppg = format.pixelsPerGroup, bpg = format.planes[0].bytesPerGroup;
    for (unsigned x = 0; x < width; src += bpg) {
        for (unsigned k = 0; k < ppg && x < width; ++k, ++x)
            dst[x] = src[format.yOffset[k]];
    }
}

template<typename Copy>
void forChromaRows(const PixelFormatInfo &format, unsigned rows, unsigned samples, Copy copy)
{
    const unsigned cbStep = chromaStep(format, format.cbPlane), crStep = chromaStep(format, format.crPlane);
    for (unsigned row = 0; row < rows; ++row) {
        for (unsigned c = 0; c < samples; ++c)
            copy(row, c, c * cbStep + format.cbOffset, c * crStep + format.crOffset);
    }
}

} // namespace

YcbcrImage ycbcrImageFor(const PixelFormatInfo &format, unsigned width, unsigned height)
{
    return YcbcrImage::allocate(width, height, format.hSubSampling, format.vSubSampling,
                                format.cbOffset != kNoComponent);
}

Status packYcbcr(const YcbcrImage &image, const FrameView &frame)
{
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding != ColourEncoding::Yuv)
        return wrongKind(frame, "a Y'CbCr format");
    const bool hasChroma = format.cbOffset != kNoComponent;
    if (!sameSize(image, frame) ||
        (hasChroma && (!image.hasChroma || image.hSub != format.hSubSampling || image.vSub != format.vSubSampling)))
        return makeError(ErrorCode::InvalidArgument, "image does not match the " + std::string(format.name) + " frame");
    for (unsigned y = 0; y < image.height; ++y)
        packLumaRow(format, &image.y[size_t(y) * image.width], image.width,
                    frame.planes[0].data + size_t(y) * frame.planes[0].stride);
    if (!hasChroma)
        return Ok{};
    const PlaneView &cbPlane = frame.planes[format.cbPlane], &crPlane = frame.planes[format.crPlane];
    const unsigned cw = image.chromaWidth();
    forChromaRows(format, image.chromaHeight(), cw, [&](unsigned row, unsigned c, size_t cbAt, size_t crAt) {
        cbPlane.data[size_t(row) * cbPlane.stride + cbAt] = image.cb[size_t(row) * cw + c];
        crPlane.data[size_t(row) * crPlane.stride + crAt] = image.cr[size_t(row) * cw + c];
    });
    return Ok{};
}

Status unpackYcbcr(const FrameView &frame, YcbcrImage &image)
{
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding != ColourEncoding::Yuv)
        return wrongKind(frame, "a Y'CbCr format");
    image.reshape(frame.width, frame.height, format.hSubSampling, format.vSubSampling, format.cbOffset != kNoComponent);
    for (unsigned y = 0; y < image.height; ++y)
        unpackLumaRow(format, frame.planes[0].data + size_t(y) * frame.planes[0].stride, image.width,
                      &image.y[size_t(y) * image.width]);
    if (!image.hasChroma)
        return Ok{};
    const PlaneView &cbPlane = frame.planes[format.cbPlane], &crPlane = frame.planes[format.crPlane];
    const unsigned cw = image.chromaWidth();
    forChromaRows(format, image.chromaHeight(), cw, [&](unsigned row, unsigned c, size_t cbAt, size_t crAt) {
        image.cb[size_t(row) * cw + c] = cbPlane.data[size_t(row) * cbPlane.stride + cbAt];
        image.cr[size_t(row) * cw + c] = crPlane.data[size_t(row) * crPlane.stride + crAt];
    });
    return Ok{};
}

Result<YcbcrImage> unpackYcbcr(const FrameView &frame)
{
    YcbcrImage image;
    if (auto unpacked = unpackYcbcr(frame, image); !unpacked)
        return unpacked.error();
    return image;
}

Status packRgb(const RgbImage &image, const FrameView &frame)
{
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding != ColourEncoding::Rgb)
        return wrongKind(frame, "an RGB format");
    if (image.width != frame.width || image.height != frame.height)
        return makeError(ErrorCode::InvalidArgument, "image does not match the " + std::string(format.name) + " frame");
    const unsigned bpp = format.planes[0].bytesPerGroup;
    for (unsigned y = 0; y < image.height; ++y) {
        const uint8_t *src = image.row(y);
        uint8_t *dst = frame.planes[0].data + size_t(y) * frame.planes[0].stride;
        for (unsigned x = 0; x < image.width; ++x, src += 3, dst += bpp) {
            if (bpp == 4)
                dst[0] = dst[1] = dst[2] = dst[3] = 0; // X bytes
            dst[format.rOffset] = src[0];
            dst[format.gOffset] = src[1];
            dst[format.bOffset] = src[2];
            if (format.aOffset != kNoComponent)
                dst[format.aOffset] = 255;
        }
    }
    return Ok{};
}

Status unpackRgb(const FrameView &frame, RgbImage &image)
{
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    const PixelFormatInfo &format = *frame.format;
    if (format.encoding != ColourEncoding::Rgb)
        return wrongKind(frame, "an RGB format");
    image.reshape(frame.width, frame.height);
    const unsigned bpp = format.planes[0].bytesPerGroup;
    for (unsigned y = 0; y < image.height; ++y) {
        const uint8_t *src = frame.planes[0].data + size_t(y) * frame.planes[0].stride;
        uint8_t *dst = image.row(y);
        for (unsigned x = 0; x < image.width; ++x, src += bpp, dst += 3) {
            dst[0] = src[format.rOffset];
            dst[1] = src[format.gOffset];
            dst[2] = src[format.bOffset];
        }
    }
    return Ok{};
}

Result<RgbImage> unpackRgb(const FrameView &frame)
{
    RgbImage image;
    if (auto unpacked = unpackRgb(frame, image); !unpacked)
        return unpacked.error();
    return image;
}

} // namespace overlayd
