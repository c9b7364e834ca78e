// SPDX-License-Identifier: Apache-2.0
// JpegEncoder with the TurboJPEG API: Y'CbCr frames through tjCompressFromYUVPlanes from JfifPlanes, RGB frames
// through tjCompress2 (which converts to full-range BT.601 itself).
#include "media/jpeg/jpeg_encoder.h"

#include <turbojpeg.h>

#include <string>

namespace overlayd {

namespace {

// The JPEG subsampling that keeps a Y'CbCr format's own, from its table entry; -1 when JPEG has none.
int turboSubsampling(const PixelFormatInfo &f)
{
    if (f.cbOffset == kNoComponent)
        return TJSAMP_GRAY;
    if (f.hSubSampling == 2 && f.vSubSampling == 2)
        return TJSAMP_420;
    if (f.hSubSampling == 2 && f.vSubSampling == 1)
        return TJSAMP_422;
    if (f.hSubSampling == 1 && f.vSubSampling == 1)
        return TJSAMP_444;
    return -1;
}

// libjpeg-turbo's pixel format with the table entry's byte order (an X or A byte is skipped either way); -1 if none.
int turboPixelFormat(const PixelFormatInfo &f)
{
    for (int p = 0; p < TJ_NUMPF; ++p) {
        if (tjPixelSize[p] == f.planes[0].bytesPerGroup && tjRedOffset[p] == f.rOffset &&
            tjGreenOffset[p] == f.gOffset && tjBlueOffset[p] == f.bOffset)
            return p;
    }
    return -1;
}

std::string describe(const FrameView &frame)
{
    return std::to_string(frame.width) + "x" + std::to_string(frame.height) + " " + std::string(frame.format->name);
}

Error unsupported(const FrameView &frame)
{
    return makeError(ErrorCode::Unsupported, "JPEG encoder: libjpeg-turbo cannot take " + describe(frame));
}

} // namespace

void JpegEncoder::HandleDeleter::operator()(void *handle) const
{
    tjDestroy(handle);
}

Result<JpegEncoder> JpegEncoder::create(JpegChroma chroma)
{
    tjhandle handle = tjInitCompress();
    if (!handle)
        return makeError(ErrorCode::Io, std::string("JPEG encoder: libjpeg-turbo: ") + tjGetErrorStr2(nullptr));
    return JpegEncoder(handle, chroma);
}

Status JpegEncoder::encode(const FrameView &frame, Colorimetry colorimetry, int quality, std::vector<uint8_t> &out)
{
    if (quality < 1 || quality > 100)
        return makeError(ErrorCode::InvalidArgument, "JPEG quality " + std::to_string(quality) + " is not in 1..100");
    if (auto checked = checkFrame(frame); !checked)
        return checked;
    unsigned long size = 0;
    auto compressed = frame.format->encoding == ColourEncoding::Rgb ? compressRgb(frame, quality, size)
                                                                    : compressYcbcr(frame, colorimetry, quality, size);
    if (!compressed)
        return compressed;
    out.assign(jpeg_.data(), jpeg_.data() + size);
    return Ok{};
}

Status JpegEncoder::compressYcbcr(const FrameView &frame, Colorimetry colorimetry, int quality, unsigned long &size)
{
    int subsampling = turboSubsampling(*frame.format);
    if (subsampling < 0)
        return unsupported(frame);
    if (mapping_.colorimetry() != colorimetry)
        mapping_ = JfifMapping(colorimetry);
    if (auto gathered = planes_.gather(frame, mapping_); !gathered)
        return gathered;
    const unsigned char *planes[3] = {planes_.data()[0], planes_.data()[1], planes_.data()[2]};
    std::array<int, 3> strides = planes_.strides();
    // An odd height would need a padded luma row for the last chroma row: such frames keep their 4:2:2.
    if (chroma_ == JpegChroma::Halved && subsampling == TJSAMP_422 && frame.height % 2 == 0) {
        halveChroma(frame, planes, strides);
        subsampling = TJSAMP_420;
    }
    unsigned char *buffer = reserve(frame, subsampling);
    size = jpeg_.size();
    if (tjCompressFromYUVPlanes(handle_.get(), planes, int(frame.width), strides.data(), int(frame.height), subsampling,
                                &buffer, &size, quality, TJFLAG_NOREALLOC) != 0)
        return failed(frame);
    return Ok{};
}

Status JpegEncoder::compressRgb(const FrameView &frame, int quality, unsigned long &size)
{
    const int pixelFormat = turboPixelFormat(*frame.format);
    if (pixelFormat < 0)
        return unsupported(frame);
    unsigned char *buffer = reserve(frame, TJSAMP_420);
    size = jpeg_.size();
    if (tjCompress2(handle_.get(), frame.planes[0].data, int(frame.width), int(frame.planes[0].stride),
                    int(frame.height), pixelFormat, &buffer, &size, TJSAMP_420, quality, TJFLAG_NOREALLOC) != 0)
        return failed(frame);
    return Ok{};
}

void JpegEncoder::halveChroma(const FrameView &frame, const unsigned char *planes[3], std::array<int, 3> &strides)
{
    const size_t width = (size_t(frame.width) + 1) / 2, rows = frame.height / 2;
    for (unsigned c = 0; c < 2; ++c) {
        std::vector<uint8_t> &out = halved_[c];
        out.resize(width * rows); // sized once for a steady stream
        const size_t stride = size_t(strides[c + 1]);
        for (size_t y = 0; y < rows; ++y) {
            const uint8_t *top = planes[c + 1] + 2 * y * stride, *bottom = top + stride;
            uint8_t *row = out.data() + y * width;
            for (size_t x = 0; x < width; ++x)
                row[x] = uint8_t((unsigned(top[x]) + bottom[x] + 1) / 2);
        }
        planes[c + 1] = out.data();
        strides[c + 1] = int(width);
    }
}

// With TJFLAG_NOREALLOC libjpeg-turbo writes into our buffer and fails rather than grow it, so it must hold the
// worst case; it only ever grows, so a steady stream sizes it once.
unsigned char *JpegEncoder::reserve(const FrameView &frame, int subsampling)
{
    const size_t bound = tjBufSize(int(frame.width), int(frame.height), subsampling);
    if (jpeg_.size() < bound)
        jpeg_.resize(bound);
    return jpeg_.data();
}

Status JpegEncoder::failed(const FrameView &frame) const
{
    return makeError(ErrorCode::Io,
                     "JPEG encoder: " + describe(frame) + " does not compress: " + tjGetErrorStr2(handle_.get()));
}

} // namespace overlayd
