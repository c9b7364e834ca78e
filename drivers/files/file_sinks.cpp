// SPDX-License-Identifier: Apache-2.0
// The raw sink (rows packed, planes in the table's order: the layout raw replay reads) and the null sink.
#include "drivers/files/file_sinks.h"

#include "drivers/files/file_io.h"
#include "drivers/files/sink_file.h"

namespace overlayd {

namespace {

class RawSink : public FrameSink
{
public:
    explicit RawSink(const SinkOptions &options) : path_(options.path), file_(options.path) {}

    Status open(const StreamFormat &) override
    {
        // The first open truncates; a re-open (format change) keeps appending to the same file.
        if (auto opened = file_.open(opened_); !opened)
            return opened;
        opened_ = true;
        return Ok{};
    }

    Status write(const FrameView &frame, const FrameMetadata &) override
    {
        if (auto out = file_.get(); !out)
            return out.error();
        if (auto checked = checkFrame(frame); !checked)
            return checked;
        const PixelFormatInfo &format = *frame.format;
        for (unsigned p = 0; p < format.numPlanes; ++p) {
            const size_t rowBytes = format.minStride(p, frame.width);
            const unsigned rows = format.planeHeight(p, frame.height);
            if (frame.planes[p].stride == rowBytes) { // packed rows: the plane in one write, not one per row
                if (auto status = file_.write(frame.planes[p].data, rowBytes * rows); !status)
                    return status;
                continue;
            }
            for (unsigned y = 0; y < rows; ++y) {
                const uint8_t *row = frame.planes[p].data + size_t(y) * frame.planes[p].stride;
                if (auto status = file_.write(row, rowBytes); !status)
                    return status;
            }
        }
        return Ok{};
    }

    Status close() override { return file_.close(); }

    std::string describe() const override { return "raw " + path_; }

private:
    std::string path_;
    SinkFile file_;
    bool opened_ = false;
};

class NullSink : public FrameSink
{
public:
    Status open(const StreamFormat &) override { return Ok{}; }
    Status write(const FrameView &, const FrameMetadata &) override
    {
        ++frames_;
        return Ok{};
    }
    Status close() override { return Ok{}; }
    std::string describe() const override { return "null (" + std::to_string(frames_) + " frames)"; }
    bool writesInline() const override { return true; }

private:
    uint64_t frames_ = 0;
};

} // namespace

Result<std::unique_ptr<FrameSink>> makeRawSink(const SinkOptions &options)
{
    if (options.path.empty())
        return makeError(ErrorCode::InvalidArgument, "the raw sink needs a path");
    return std::unique_ptr<FrameSink>(std::make_unique<RawSink>(options));
}

Result<std::unique_ptr<FrameSink>> makeNullSink(const SinkOptions &)
{
    return std::unique_ptr<FrameSink>(std::make_unique<NullSink>());
}

} // namespace overlayd
