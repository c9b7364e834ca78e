// SPDX-License-Identifier: Apache-2.0
// The format of a file is its signature (never its name): PNG's eight bytes, JPEG's SOI marker.
#include "media/codec/image_codec.h"

#include <string>

#include "media/codec/formats.h"

namespace overlayd {

namespace {

Error neither()
{
    return makeError(ErrorCode::Malformed, "neither a PNG nor a JPEG file (no signature of either)");
}

} // namespace

Status checkSide(const ImageFileInfo &info, unsigned maxSide)
{
    if (info.width <= maxSide && info.height <= maxSide)
        return Ok{};
    return makeError(ErrorCode::Unsupported, "the image is " + std::to_string(info.width) + "x" +
                                                 std::to_string(info.height) + "; at most " + std::to_string(maxSide) +
                                                 " pixels a side");
}

Result<ImageFileInfo> readImageInfo(std::span<const uint8_t> file)
{
    if (isPng(file))
        return pngInfo(file);
    if (isJpeg(file))
        return jpegInfo(file);
    return neither();
}

Result<DecodedImage> decodeImage(std::span<const uint8_t> file, ImageChannels channels, unsigned maxSide)
{
    if (isPng(file))
        return decodePng(file, channels, maxSide);
    if (isJpeg(file))
        return decodeJpeg(file, channels, maxSide);
    return neither();
}

} // namespace overlayd
