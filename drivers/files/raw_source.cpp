// SPDX-License-Identifier: Apache-2.0
// Raw replay: frames back to back, each laid out as makeFrameLayout packs it (rows packed, planes in the table's
// order), in the configured format, size and fps. The file's bytes are read straight into the frame.
#include "drivers/files/replay_base.h"

#include <cmath>

#include "drivers/files/file_io.h"

namespace overlayd {

namespace {

class RawSource : public ReplaySource
{
public:
    using ReplaySource::ReplaySource;

protected:
    Result<StreamFormat> open() override;
    void close() override { file_.reset(); }
    Status read(uint64_t index, FrameBuffer &buffer) override;
    Status rewind() override;
    const char *kind() const override { return "raw"; }

private:
    UniqueFile file_;
};

Result<StreamFormat> RawSource::open()
{
    auto file = openForReading(options_.replay.path);
    if (!file)
        return file.error();
    file_ = std::move(*file);
    return StreamFormat{
        options_.pixelFormat, options_.width, options_.height, 0, options_.colorimetry.value_or(Colorimetry{}),
        options_.fps};
}

Status RawSource::read(uint64_t index, FrameBuffer &buffer)
{
    auto got = readUpTo(file_.get(), buffer.data(), buffer.size(), options_.replay.path);
    if (!got)
        return got.error();
    if (*got == 0)
        return makeError(ErrorCode::EndOfStream, options_.replay.path + ": end of file");
    if (*got < buffer.size())
        return malformed(index, "truncated (" + std::to_string(*got) + " of " + std::to_string(buffer.size()) +
                                    " bytes of a " + format_.describe() + " frame)");
    return Ok{};
}

Status RawSource::rewind()
{
    if (std::fseek(file_.get(), 0, SEEK_SET) != 0)
        return makeError(ErrorCode::Io, options_.replay.path + ": cannot seek back to the first frame");
    return Ok{};
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeRawSource(const SourceOptions &options)
{
    const PixelFormatInfo *format = options.pixelFormat;
    if (!(options.fps > 0.0 && std::isfinite(options.fps)))
        return makeError(ErrorCode::InvalidArgument,
                         "raw replay needs fps > 0 (got " + std::to_string(options.fps) + ")");
    if (auto layout = makeFrameLayout(*format, options.width, options.height); !layout)
        return layout.error();
    return std::unique_ptr<FrameSource>(std::make_unique<RawSource>(options));
}

} // namespace overlayd
