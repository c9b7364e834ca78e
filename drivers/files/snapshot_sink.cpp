// SPDX-License-Identifier: Apache-2.0
// Snapshot sink: one PNG or JPEG (by extension) per `every` frames, numbered by the frame's sequence number when
// the path holds %d, else the same file replaced atomically each time.
#include "drivers/files/file_sinks.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/replace_file.h"
#include "drivers/files/path_pattern.h"
#include "media/codec/image_codec.h"
#include "media/convert/frame_convert.h"

namespace overlayd {

namespace {

class SnapshotSink : public FrameSink
{
public:
    SnapshotSink(const SinkOptions &options, std::string extension)
        : options_(options), extension_(std::move(extension))
    {}

    Status open(const StreamFormat &) override { return Ok{}; }
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override { return Ok{}; }
    std::string describe() const override
    {
        return "snapshot " + options_.path + " every " + std::to_string(options_.every) + " frames";
    }

private:
    Result<std::vector<uint8_t>> encode(const FrameView &frame, Colorimetry colorimetry) const;

    SinkOptions options_;
    std::string extension_;
    uint64_t received_ = 0;
};

Result<std::vector<uint8_t>> SnapshotSink::encode(const FrameView &frame, Colorimetry colorimetry) const
{
    auto rgb = frameToRgb(frame, colorimetry);
    if (!rgb)
        return rgb.error();
    auto bytes = extension_ == ".png" ? encodePng(*rgb) : encodeJpeg(*rgb, int(options_.jpegQuality));
    if (!bytes)
        return makeError(ErrorCode::Io, options_.path + ": image encoding failed: " + bytes.error().message);
    return bytes;
}

Status SnapshotSink::write(const FrameView &frame, const FrameMetadata &metadata)
{
    if (received_++ % options_.every != 0)
        return Ok{};
    auto path = formatIndex(options_.path, metadata.sequence);
    if (!path)
        return path.error();
    auto bytes = encode(frame, metadata.colorimetry);
    if (!bytes)
        return bytes.error();
    // Unsynced: a viewer must never see half an image, but a power cut may lose the newest snapshot.
    return replaceFileContents(*path, std::string_view(reinterpret_cast<const char *>(bytes->data()), bytes->size()),
                               Durability::Unsynced);
}

} // namespace

Result<std::unique_ptr<FrameSink>> makeSnapshotSink(const SinkOptions &options)
{
    const std::string extension = lowerExtension(options.path);
    if (extension != ".png" && extension != ".jpg" && extension != ".jpeg")
        return makeError(ErrorCode::InvalidArgument,
                         "snapshot path '" + options.path + "' must end in .png, .jpg or .jpeg");
    if (options.every == 0)
        return makeError(ErrorCode::InvalidArgument, "snapshot every must be >= 1");
    if (options.jpegQuality < 1 || options.jpegQuality > 100)
        return makeError(ErrorCode::InvalidArgument,
                         "jpeg_quality must be in 1..100 (got " + std::to_string(options.jpegQuality) + ")");
    if (auto path = formatIndex(options.path, 0); !path)
        return path.error();
    return std::unique_ptr<FrameSink>(std::make_unique<SnapshotSink>(options, extension));
}

} // namespace overlayd
