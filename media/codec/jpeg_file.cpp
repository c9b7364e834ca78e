// SPDX-License-Identifier: Apache-2.0
// JPEG files through libjpeg-turbo's TurboJPEG API (2.1 in Debian 12): tjDecompressHeader3 gives the size before
// anything is allocated, tjDecompress2 the pixels, tjCompress2 the snapshots. TurboJPEG returns errors (it keeps
// libjpeg's longjmp inside itself), so no setjmp is needed here.
#include "media/codec/formats.h"
#include "media/codec/image_codec.h"

#include <turbojpeg.h>

#include <memory>
#include <string>

namespace overlayd {

namespace {

struct HandleDeleter {
    void operator()(void *handle) const { tjDestroy(handle); }
};
using TurboHandle = std::unique_ptr<void, HandleDeleter>;

struct JpegHeader {
    int width = 0, height = 0, subsampling = 0, colourspace = 0;
};

Error failed(tjhandle handle, ErrorCode code = ErrorCode::Malformed)
{
    return makeError(code, std::string("JPEG: ") + tjGetErrorStr2(handle));
}

Error noTurbo()
{
    return makeError(ErrorCode::Io, std::string("JPEG: libjpeg-turbo cannot make a codec: ") + tjGetErrorStr2(nullptr));
}

Result<JpegHeader> readHeader(tjhandle handle, std::span<const uint8_t> file)
{
    JpegHeader header;
    if (tjDecompressHeader3(handle, file.data(), (unsigned long)file.size(), &header.width, &header.height,
                            &header.subsampling, &header.colourspace) != 0)
        return failed(handle);
    if (header.width <= 0 || header.height <= 0)
        return makeError(ErrorCode::Malformed, "JPEG: the header gives no size");
    return header;
}

} // namespace

bool isJpeg(std::span<const uint8_t> file)
{
    return file.size() >= 3 && file[0] == 0xff && file[1] == 0xd8 && file[2] == 0xff;
}

Result<ImageFileInfo> jpegInfo(std::span<const uint8_t> file)
{
    TurboHandle handle(tjInitDecompress());
    if (!handle)
        return noTurbo();
    auto header = readHeader(handle.get(), file);
    if (!header)
        return header.error();
    return ImageFileInfo{ImageFileType::Jpeg, unsigned(header->width), unsigned(header->height)};
}

Result<DecodedImage> decodeJpeg(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide)
{
    TurboHandle handle(tjInitDecompress());
    if (!handle)
        return noTurbo();
    auto header = readHeader(handle.get(), file);
    if (!header)
        return header.error();
    if (header->colourspace == TJCS_CMYK || header->colourspace == TJCS_YCCK)
        return makeError(ErrorCode::Unsupported, "JPEG: CMYK files are not supported (greyscale, YCbCr or RGB)");
    const ImageFileInfo info{ImageFileType::Jpeg, unsigned(header->width), unsigned(header->height)};
    if (auto fits = checkSide(info, maxSide); !fits)
        return fits.error();
    DecodedImage image{info.width, info.height, channels,
                       std::vector<uint8_t>(size_t(info.width) * info.height * size_t(channels))};
    const int format = channels == ImageChannels::Rgba ? TJPF_RGBA : TJPF_RGB; // RGBA: alpha 255
    // A warning (data missing or extraneous, which libjpeg patches up with grey) is an error here: a file that
    // decodes only that way is refused with the reason, as a truncated PNG is. LIMITSCANS: a progressive file
    // with thousands of scans is a way to burn a core, not a picture.
    if (tjDecompress2(handle.get(), file.data(), (unsigned long)file.size(), image.pixels.data(), header->width, 0,
                      header->height, format, TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0)
        return failed(handle.get());
    return image;
}

} // namespace overlayd
namespace overlayd {

Result<std::vector<uint8_t>> encodeJpeg(const RgbImage &image, int quality)
{
    if (quality < 1 || quality > 100)
        return makeError(ErrorCode::InvalidArgument, "JPEG quality " + std::to_string(quality) + " is not in 1..100");
    if (image.width == 0 || image.height == 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        return makeError(ErrorCode::InvalidArgument, "JPEG: an empty or inconsistent image");
    TurboHandle handle(tjInitCompress());
    if (!handle)
        return noTurbo();
    // Compressed straight into a buffer of the worst-case size, then trimmed: no copy, no TurboJPEG allocation.
    // ACCURATEDCT: libjpeg's default DCT (TurboJPEG's own default is the fast one), so that a snapshot is byte for
    // byte what OpenCV's imencode wrote at the same quality before.
    std::vector<uint8_t> bytes(tjBufSize(int(image.width), int(image.height), TJSAMP_420));
    unsigned char *out = bytes.data();
    unsigned long size = bytes.size();
    if (tjCompress2(handle.get(), image.rgb.data(), int(image.width), 0, int(image.height), TJPF_RGB, &out, &size,
                    TJSAMP_420, quality, TJFLAG_NOREALLOC | TJFLAG_ACCURATEDCT) != 0)
        return failed(handle.get(), ErrorCode::Io);
    bytes.resize(size);
    return bytes;
}

} // namespace overlayd
