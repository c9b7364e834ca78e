// SPDX-License-Identifier: Apache-2.0
// Image-sequence replay: PNG/JPEG files decoded by media/codec and converted to the configured pixel format. The first
// image sets the frame size; the sequence ends at the first missing number.
#include "drivers/files/replay_base.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include "drivers/files/file_io.h"
#include "drivers/files/path_pattern.h"
#include "media/codec/image_codec.h"
#include "media/convert/frame_convert.h"

namespace overlayd {

namespace {

// A PNG or JPEG frame larger than this is refused before it is read (16384 x 16384 RGB is 768 MiB uncompressed;
// a real frame compresses to a small part of its pixels).
constexpr uintmax_t kMaxImageFileBytes = 256u << 20;

class ImageSource : public ReplaySource
{
public:
    using ReplaySource::ReplaySource;

protected:
    Result<StreamFormat> open() override;
    void close() override {}
    Status read(uint64_t index, FrameBuffer &buffer) override;
    Status rewind() override { return Ok{}; }
    const char *kind() const override { return "image"; }

private:
    // RGB pixels of one file; EndOfStream when it does not exist.
    Result<RgbImage> decode(uint64_t index) const;
    std::string pathOf(uint64_t index) const;
};

std::string ImageSource::pathOf(uint64_t index) const
{
    auto path = formatIndex(options_.replay.path, options_.replay.firstIndex + index);
    return path ? *path : options_.replay.path; // checked by the factory
}

Result<RgbImage> ImageSource::decode(uint64_t index) const
{
    const std::string path = pathOf(index);
    // Without %d the "sequence" is one image.
    std::error_code error;
    if ((index > 0 && !hasIndexPattern(options_.replay.path)) || !std::filesystem::exists(path, error))
        return makeError(ErrorCode::EndOfStream, path + ": no such image (end of the sequence)");
    auto file = readWholeFile(path, kMaxImageFileBytes);
    if (!file && file.error().code == ErrorCode::Malformed)
        return malformed(index, file.error().message);
    if (!file)
        return file.error();
    // The header's size is checked before the pixels are allocated.
    auto decoded = decodeImage(*file, ImageChannels::Rgb, kMaxFrameDimension);
    if (!decoded)
        return malformed(index, path + " does not decode: " + decoded.error().message);
    return RgbImage{decoded->width, decoded->height, std::move(decoded->pixels)};
}

Result<StreamFormat> ImageSource::open()
{
    auto first = decode(0);
    if (!first && first.error().code == ErrorCode::EndOfStream)
        return makeError(ErrorCode::NotFound, pathOf(0) + ": the image sequence's first file does not exist");
    if (!first)
        return first.error();
    return StreamFormat{
        options_.pixelFormat, first->width, first->height, 0, options_.colorimetry.value_or(Colorimetry{}),
        options_.fps};
}

Status ImageSource::read(uint64_t index, FrameBuffer &buffer)
{
    auto image = decode(index);
    if (!image)
        return image.error();
    if (image->width != format_.width || image->height != format_.height)
        return malformed(index, pathOf(index) + " is " + std::to_string(image->width) + "x" +
                                    std::to_string(image->height) + ", the sequence is " +
                                    std::to_string(format_.width) + "x" + std::to_string(format_.height));
    return rgbToFrame(*image, format_.colorimetry, buffer.view());
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeImageSource(const SourceOptions &options)
{
    if (!(options.fps > 0.0 && std::isfinite(options.fps)))
        return makeError(ErrorCode::InvalidArgument,
                         "image replay needs fps > 0 (got " + std::to_string(options.fps) + ")");
    if (auto path = formatIndex(options.replay.path, 0); !path)
        return path.error();
    return std::unique_ptr<FrameSource>(std::make_unique<ImageSource>(options));
}

} // namespace overlayd
