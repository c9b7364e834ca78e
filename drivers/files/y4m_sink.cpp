// SPDX-License-Identifier: Apache-2.0
// Y4M sink: planar 8-bit Y'CbCr after a FRAME line; formats that are not planar are unpacked (NV12 -> I420
// planes, YUYV -> 4:2:2 planes) and RGB is encoded at 4:4:4, so that every format writes a file ffmpeg reads.
#include "drivers/files/file_sinks.h"

#include "drivers/files/file_io.h"
#include "drivers/files/sink_file.h"
#include "drivers/files/y4m_header.h"
#include "media/convert/frame_convert.h"

namespace overlayd {

namespace {

constexpr std::string_view kFrameLine = "FRAME\n";

class Y4mSink : public FrameSink
{
public:
    explicit Y4mSink(const SinkOptions &options) : path_(options.path), file_(options.path) {}

    Status open(const StreamFormat &format) override;
    Status write(const FrameView &frame, const FrameMetadata &metadata) override;
    Status close() override;
    std::string describe() const override { return "Y4M " + (toStdout() ? std::string("stdout") : path_); }

private:
    bool toStdout() const { return path_ == "-"; }
    // To stdout, or to the file (a FIFO's reader may have just opened it: SinkFile writes its header first).
    Status put(const void *data, size_t size)
    {
        return toStdout() ? writeAll(stdout, data, size, path_) : file_.write(data, size);
    }

    std::string path_;
    SinkFile file_;
    bool open_ = false;
    std::string header_; // the header written, if any: a re-open with the same stream appends
    Colorimetry colorimetry_{};
    // Kept from frame to frame: a fresh image per frame cost a page fault per 4 KiB, as much system time as the
    // conversion itself (docs/speed.md).
    YcbcrImage samples_;
    RgbImage rgbScratch_;
};

Status Y4mSink::open(const StreamFormat &format)
{
    if (!format.format)
        return makeError(ErrorCode::InvalidArgument, "Y4M sink needs a pixel format");
    Y4mHeader header{
        format.width, format.height, 30, 1, Y4mChroma::C420, y4mChromaTagFor(*format.format), format.colorimetry.range};
    fpsToRatio(format.fps, header.fpsNum, header.fpsDen);
    const std::string line = formatY4mHeader(header);
    const bool append = line == header_;
    if (toStdout() && !header_.empty() && !append)
        return makeError(ErrorCode::Unsupported, "a Y4M stream on stdout cannot change format (" +
                                                     header_.substr(0, header_.size() - 1) + " -> " +
                                                     format.describe() + ")");
    colorimetry_ = format.colorimetry;
    if (toStdout()) {
        open_ = true;
        if (append)
            return Ok{};
        header_ = line;
        return writeAll(stdout, line.data(), line.size(), path_);
    }
    if (auto opened = file_.open(append, append ? std::string() : line); !opened)
        return opened;
    open_ = true;
    header_ = line;
    return Ok{};
}

Status Y4mSink::write(const FrameView &frame, const FrameMetadata &)
{
    if (!open_)
        return makeError(ErrorCode::InvalidArgument, describe() + " is not open");
    if (!toStdout()) { // a FIFO without a reader: no conversion for a frame nobody takes
        if (auto out = file_.get(); !out)
            return out.error();
    }
    if (auto converted = frameToYcbcr(frame, colorimetry_, samples_, rgbScratch_); !converted)
        return converted;
    if (auto status = put(kFrameLine.data(), kFrameLine.size()); !status)
        return status;
    for (const std::vector<uint8_t> *plane : {&samples_.y, &samples_.cb, &samples_.cr}) {
        if (auto status = put(plane->data(), plane->size()); !status)
            return status;
    }
    return Ok{};
}

Status Y4mSink::close()
{
    if (!open_)
        return Ok{};
    open_ = false;
    if (toStdout())
        return std::fflush(stdout) == 0 ? Status(Ok{}) : makeError(ErrorCode::Io, "stdout: flush failed");
    return file_.close();
}

} // namespace

const char *y4mChromaTagFor(const PixelFormatInfo &format)
{
    if (format.encoding == ColourEncoding::Rgb)
        return "444";
    if (format.cbOffset == kNoComponent)
        return "mono";
    return format.vSubSampling == 2 ? "420jpeg" : "422";
}

Result<std::unique_ptr<FrameSink>> makeY4mSink(const SinkOptions &options)
{
    if (options.path.empty())
        return makeError(ErrorCode::InvalidArgument, "the Y4M sink needs a path (or \"-\" for stdout)");
    return std::unique_ptr<FrameSink>(std::make_unique<Y4mSink>(options));
}

} // namespace overlayd
