// SPDX-License-Identifier: Apache-2.0
// Y4M replay: 4:2:0 frames come out as YUV420, 4:2:2 repacked losslessly to YUYV, mono as GREY; 4:4:4 has no
// format in the table, so it is converted to the configured pixel format (chroma averaged per macropixel).
#include "drivers/files/replay_base.h"

#include "drivers/files/file_io.h"
#include "drivers/files/y4m_header.h"
#include "media/convert/frame_convert.h"

namespace overlayd {

namespace {

constexpr size_t kMaxLine = 4096; // headers are short; a longer line is not a Y4M file

class Y4mSource : public ReplaySource
{
public:
    using ReplaySource::ReplaySource;

protected:
    Result<StreamFormat> open() override;
    void close() override { file_.reset(); }
    Status read(uint64_t index, FrameBuffer &buffer) override;
    Status rewind() override;
    const char *kind() const override { return "Y4M"; }

private:
    // A line without its newline; nothing at a clean end of file.
    Result<std::optional<std::string>> readLine(uint64_t index);
    const PixelFormatInfo *outputFormat() const;

    UniqueFile file_;
    Y4mHeader header_;
    YcbcrImage samples_;
    long dataStart_ = 0;
};

Result<std::optional<std::string>> Y4mSource::readLine(uint64_t index)
{
    std::string line;
    for (int c; (c = std::fgetc(file_.get())) != '\n';) {
        if (c == EOF) {
            if (std::ferror(file_.get()))
                return makeError(ErrorCode::Io, options_.replay.path + ": read failed");
            if (line.empty())
                return std::optional<std::string>();
            return malformed(index, "truncated in its FRAME line");
        }
        if (line.size() >= kMaxLine)
            return malformed(index, "line longer than " + std::to_string(kMaxLine) + " bytes");
        line.push_back(char(c));
    }
    return std::optional<std::string>(std::move(line));
}

const PixelFormatInfo *Y4mSource::outputFormat() const
{
    switch (header_.chroma) {
    case Y4mChroma::C420:
        return pixelFormatFromName("YUV420");
    case Y4mChroma::C422:
        return pixelFormatFromName("YUYV");
    case Y4mChroma::Mono:
        return pixelFormatFromName("GREY");
    case Y4mChroma::C444:
        break;
    }
    return options_.pixelFormat;
}

Result<StreamFormat> Y4mSource::open()
{
    auto file = openForReading(options_.replay.path);
    if (!file)
        return file.error();
    file_ = std::move(*file);
    auto line = readLine(0);
    if (!line || !*line) {
        close();
        return makeError(ErrorCode::Malformed, options_.replay.path + ": Y4M header missing or truncated");
    }
    auto header = parseY4mHeader(**line, options_.replay.path);
    if (!header) {
        close();
        return header.error();
    }
    header_ = *header;
    dataStart_ = std::ftell(file_.get());
    samples_ = YcbcrImage::allocate(header_.width, header_.height, header_.hSub(), header_.vSub(),
                                    header_.chroma != Y4mChroma::Mono);
    Colorimetry colorimetry = options_.colorimetry.value_or(Colorimetry{});
    if (!options_.colorimetry && header_.range)
        colorimetry.range = *header_.range;
    return StreamFormat{
        outputFormat(), header_.width, header_.height, 0, colorimetry, double(header_.fpsNum) / header_.fpsDen};
}

Status Y4mSource::read(uint64_t index, FrameBuffer &buffer)
{
    auto line = readLine(index);
    if (!line)
        return line.error();
    if (!*line)
        return makeError(ErrorCode::EndOfStream, options_.replay.path + ": end of file");
    if ((*line)->substr(0, 5) != "FRAME")
        return malformed(index, "expected a FRAME marker, found '" + (*line)->substr(0, 16) + "'");
    size_t got = 0;
    for (std::vector<uint8_t> *plane : {&samples_.y, &samples_.cb, &samples_.cr}) {
        auto n = readUpTo(file_.get(), plane->data(), plane->size(), options_.replay.path);
        if (!n)
            return n.error();
        got += *n;
        if (*n < plane->size())
            return malformed(index, "truncated (" + std::to_string(got) + " of " +
                                        std::to_string(header_.frameBytes()) + " bytes)");
    }
    return ycbcrToFrame(samples_, format_.colorimetry, buffer.view());
}

Status Y4mSource::rewind()
{
    if (std::fseek(file_.get(), dataStart_, SEEK_SET) != 0)
        return makeError(ErrorCode::Io, options_.replay.path + ": cannot seek back to the first frame");
    return Ok{};
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeY4mSource(const SourceOptions &options)
{
    return std::unique_ptr<FrameSource>(std::make_unique<Y4mSource>(options));
}

} // namespace overlayd
