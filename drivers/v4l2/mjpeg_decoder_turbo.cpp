// SPDX-License-Identifier: Apache-2.0
// MjpegDecoder with libjpeg-turbo: decode to the JPEG's own YUV planes, then lay them out as YUYV or I420.
#include "drivers/v4l2/mjpeg_decoder.h"

#include <turbojpeg.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace overlayd {

namespace {

struct TjDeleter {
    void operator()(void *handle) const { tjDestroy(handle); }
};

struct SourcePlanes {
    std::array<uint8_t *, 3> data{};
    std::array<int, 3> stride{};
    unsigned hSub = 1, vSub = 1; // luma pixels per chroma sample
    bool grey = false;
};

uint8_t averageChroma(const SourcePlanes &in, unsigned plane, unsigned x0, unsigned y0, unsigned x1, unsigned y1)
{
    unsigned sum = 0, count = 0;
    for (unsigned y = y0; y < y1; ++y) {
        for (unsigned x = x0; x < x1; ++x, ++count)
            sum += in.data[plane][size_t(y / in.vSub) * in.stride[plane] + x / in.hSub];
    }
    return uint8_t((sum + count / 2) / count);
}

// Chroma sample (cx, cy) of the output covers the luma box hSub x vSub at (cx * hSub, cy * vSub).
void writeChroma(const SourcePlanes &in, const FrameView &out, unsigned cx, unsigned cy)
{
    const PixelFormatInfo &f = *out.format;
    const unsigned x0 = cx * f.hSubSampling, y0 = cy * f.vSubSampling;
    const unsigned x1 = std::min(x0 + f.hSubSampling, out.width), y1 = std::min(y0 + f.vSubSampling, out.height);
    const uint8_t cb = in.grey ? 128 : averageChroma(in, 1, x0, y0, x1, y1);
    const uint8_t cr = in.grey ? 128 : averageChroma(in, 2, x0, y0, x1, y1);
    const bool packed = f.layout == PixelLayout::PackedYuv422;
    const size_t cbAt = size_t(cy) * out.planes[f.cbPlane].stride + (packed ? cx * 4u + f.cbOffset : cx);
    const size_t crAt = size_t(cy) * out.planes[f.crPlane].stride + (packed ? cx * 4u + f.crOffset : cx);
    out.planes[f.cbPlane].data[cbAt] = cb;
    out.planes[f.crPlane].data[crAt] = cr;
}

void writeLuma(const SourcePlanes &in, const FrameView &out)
{
    const PixelFormatInfo &f = *out.format;
    for (unsigned y = 0; y < out.height; ++y) {
        const uint8_t *row = in.data[0] + size_t(y) * in.stride[0];
        uint8_t *dst = out.planes[0].data + size_t(y) * out.planes[0].stride;
        if (f.layout != PixelLayout::PackedYuv422) {
            std::memcpy(dst, row, out.width);
            continue;
        }
        for (unsigned x = 0; x < out.width; ++x)
            dst[(x / 2) * 4 + f.yOffset[x % 2]] = row[x];
    }
}

class TurboMjpegDecoder final : public MjpegDecoder
{
public:
    explicit TurboMjpegDecoder(tjhandle handle) : handle_(handle) {}
    Status decode(std::span<const uint8_t> jpeg, const FrameView &out) override;

private:
    Status decompress(std::span<const uint8_t> jpeg, uint8_t **planes, int *strides, int width, int height);

    std::unique_ptr<void, TjDeleter> handle_;
    std::vector<uint8_t> scratch_;
};

Status TurboMjpegDecoder::decompress(std::span<const uint8_t> jpeg, uint8_t **planes, int *strides, int width,
                                     int height)
{
    if (tjDecompressToYUVPlanes(handle_.get(), jpeg.data(), jpeg.size(), planes, width, strides, height, 0) != 0)
        return makeError(ErrorCode::Malformed,
                         std::string("MJPEG frame does not decode: ") + tjGetErrorStr2(handle_.get()));
    return Ok{};
}

Status TurboMjpegDecoder::decode(std::span<const uint8_t> jpeg, const FrameView &out)
{
    int width = 0, height = 0, subsamp = 0, colorspace = 0;
    if (tjDecompressHeader3(handle_.get(), jpeg.data(), jpeg.size(), &width, &height, &subsamp, &colorspace) != 0)
        return makeError(ErrorCode::Malformed,
                         std::string("MJPEG frame has no valid header: ") + tjGetErrorStr2(handle_.get()));
    if (unsigned(width) != out.width || unsigned(height) != out.height)
        return makeError(ErrorCode::Malformed, "MJPEG frame is " + std::to_string(width) + "x" +
                                                   std::to_string(height) + ", the stream " +
                                                   std::to_string(out.width) + "x" + std::to_string(out.height));
    const PixelFormatInfo &f = *out.format;
    if (subsamp == TJSAMP_420 && f.layout == PixelLayout::Planar && f.vSubSampling == 2) {
        // Same layout: decode straight into the frame.
        uint8_t *planes[3] = {out.planes[0].data, out.planes[f.cbPlane].data, out.planes[f.crPlane].data};
        int strides[3] = {int(out.planes[0].stride), int(out.planes[f.cbPlane].stride),
                          int(out.planes[f.crPlane].stride)};
        return decompress(jpeg, planes, strides, width, height);
    }
    SourcePlanes in;
    in.grey = subsamp == TJSAMP_GRAY;
    in.hSub = unsigned(tjMCUWidth[subsamp] / 8);
    in.vSub = unsigned(tjMCUHeight[subsamp] / 8);
    size_t total = 0;
    std::array<size_t, 3> offsets{};
    for (int p = 0; p < (in.grey ? 1 : 3); ++p) {
        offsets[p] = total;
        in.stride[p] = tjPlaneWidth(p, width, subsamp);
        total += size_t(in.stride[p]) * tjPlaneHeight(p, height, subsamp);
    }
    scratch_.resize(total);
    for (int p = 0; p < (in.grey ? 1 : 3); ++p)
        in.data[p] = scratch_.data() + offsets[p];
    if (auto decoded = decompress(jpeg, in.data.data(), in.stride.data(), width, height); !decoded)
        return decoded;
    writeLuma(in, out);
    for (unsigned cy = 0; cy < f.planeHeight(f.cbPlane, out.height); ++cy) {
        for (unsigned cx = 0; cx < (out.width + f.hSubSampling - 1) / f.hSubSampling; ++cx)
            writeChroma(in, out, cx, cy);
    }
    return Ok{};
}

} // namespace

Result<std::unique_ptr<MjpegDecoder>> makeMjpegDecoder()
{
    tjhandle handle = tjInitDecompress();
    if (!handle)
        return makeError(ErrorCode::Io, std::string("libjpeg-turbo: ") + tjGetErrorStr2(nullptr));
    return std::unique_ptr<MjpegDecoder>(new TurboMjpegDecoder(handle));
}

} // namespace overlayd
