// SPDX-License-Identifier: Apache-2.0
// SyntheticSource: static patterns (bars, checkerboard, the 3D scene) are rendered and converted once at start()
// and copied into each frame; the moving gradient and noise are drawn per frame. Timestamps are sequence / fps
// (not the clock) so that two runs produce the same frames and metadata.
#include "drivers/synthetic/synthetic_source.h"

#include <cmath>
#include <optional>

#include "drivers/synthetic/checker_scene.h"
#include "drivers/synthetic/patterns.h"
#include "media/convert/frame_convert.h"
#include "media/frame_pool.h"

namespace overlayd {

namespace {

constexpr unsigned kPoolFrames = 4;

const char *patternName(SyntheticPattern pattern)
{
    static constexpr const char *kNames[] = {"colour-bars", "checkerboard", "moving-gradient", "noise",
                                             "checkerboard-scene"};
    return kNames[static_cast<unsigned>(pattern)];
}

bool isStatic(SyntheticPattern pattern)
{
    return pattern != SyntheticPattern::MovingGradient && pattern != SyntheticPattern::Noise;
}

class SyntheticSource : public FrameSource
{
public:
    SyntheticSource(const SourceOptions &options, const Camera *camera, StreamFormat format)
        : options_(options.synthetic), format_(format)
    {
        if (camera)
            camera_.emplace(*camera);
    }

    Result<StreamFormat> start() override;
    void stop() override { pool_.reset(), still_.reset(); }
    int eventFd() const override { return -1; }
    Result<FrameLease> nextFrame() override;
    std::string describe() const override
    {
        return std::string("synthetic ") + patternName(options_.pattern) + " " + format_.describe();
    }

private:
    RgbImage renderStill() const;
    Status draw(uint64_t sequence, FrameBuffer &buffer);

    SyntheticOptions options_;
    std::optional<Camera> camera_; // the checkerboard scene's
    StreamFormat format_;
    std::shared_ptr<FramePool> pool_;
    std::optional<FrameBuffer> still_; // the static pattern in the stream's format
    RgbImage scratch_;                 // per-frame patterns are drawn here
    uint64_t sequence_ = 0;
    std::chrono::system_clock::time_point startWall_{};
};

Result<StreamFormat> SyntheticSource::start()
{
    auto pool = FramePool::create(format_, kPoolFrames);
    if (!pool)
        return pool.error();
    pool_ = std::move(*pool);
    sequence_ = 0;
    startWall_ = std::chrono::system_clock::now();
    if (isStatic(options_.pattern)) {
        auto still = FrameBuffer::allocate(format_);
        if (!still)
            return still.error();
        if (auto drawn = rgbToFrame(renderStill(), format_.colorimetry, still->view()); !drawn)
            return drawn.error();
        still_ = std::move(*still);
    } else {
        scratch_ = RgbImage::allocate(format_.width, format_.height);
    }
    return format_;
}

RgbImage SyntheticSource::renderStill() const
{
    switch (options_.pattern) {
    case SyntheticPattern::ColourBars:
        return colourBars(format_.width, format_.height);
    case SyntheticPattern::Checkerboard:
        return checkerboard(format_.width, format_.height, options_.checkerPx);
    default:
        return renderCheckerScene(*camera_, format_.width, format_.height, options_.checkerMetres);
    }
}

Status SyntheticSource::draw(uint64_t sequence, FrameBuffer &buffer)
{
    if (still_)
        return buffer.copyFrom(still_->view());
    if (options_.pattern == SyntheticPattern::Noise)
        noise(scratch_, options_.seed, sequence);
    else
        movingGradient(scratch_, sequence);
    return rgbToFrame(scratch_, format_.colorimetry, buffer.view());
}

Result<FrameLease> SyntheticSource::nextFrame()
{
    if (!pool_)
        return makeError(ErrorCode::InvalidArgument, "synthetic source is not started");
    if (options_.stallAfterFrames != 0 && sequence_ >= options_.stallAfterFrames)
        return makeError(ErrorCode::TryAgain, "synthetic source stalled after " +
                                                  std::to_string(options_.stallAfterFrames) +
                                                  " frames (as configured)");
    const auto index = pool_->acquire();
    if (!index)
        return makeError(ErrorCode::TryAgain, "every synthetic frame is still lent out");
    if (auto drawn = draw(sequence_, pool_->buffer(*index)); !drawn) {
        pool_->release(*index);
        return drawn.error();
    }
    FrameMetadata metadata;
    metadata.sequence = sequence_;
    // The time the frame was made, on CLOCK_MONOTONIC as a camera's is (latency is measured from it); the wall
    // clock the overlay prints advances by the stream's frame period, so a render's text does not depend on speed.
    metadata.timestamp = std::chrono::steady_clock::now().time_since_epoch();
    metadata.wallClock =
        startWall_ + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                         std::chrono::nanoseconds(std::llround(double(sequence_) * 1e9 / format_.fps)));
    metadata.colorimetry = format_.colorimetry;
    ++sequence_;
    return pool_->lend(*index, metadata);
}

Status validate(const SourceOptions &options, const Camera *camera)
{
    const SyntheticOptions &synthetic = options.synthetic;
    if (synthetic.pattern == SyntheticPattern::Checkerboard && synthetic.checkerPx == 0)
        return makeError(ErrorCode::InvalidArgument, "checker_px must be > 0");
    if (synthetic.pattern != SyntheticPattern::CheckerboardScene)
        return Ok{};
    if (!(synthetic.checkerMetres > 0.0 && std::isfinite(synthetic.checkerMetres)))
        return makeError(ErrorCode::InvalidArgument,
                         "checker_metres must be > 0 (got " + std::to_string(synthetic.checkerMetres) + ")");
    if (!camera)
        return makeError(ErrorCode::InvalidArgument, "the checkerboard-scene pattern needs a camera");
    const Viewport &viewport = camera->viewport();
    if (unsigned(viewport.frameWidth()) != options.width || unsigned(viewport.frameHeight()) != options.height)
        return makeError(ErrorCode::InvalidArgument,
                         "the camera's viewport frame is " + std::to_string(viewport.frameWidth()) + "x" +
                             std::to_string(viewport.frameHeight()) + " but the source is " +
                             std::to_string(options.width) + "x" + std::to_string(options.height));
    return Ok{};
}

} // namespace

Result<std::unique_ptr<FrameSource>> makeSyntheticSource(const SourceOptions &options, const Camera *sceneCamera)
{
    if (auto valid = validate(options, sceneCamera); !valid)
        return valid.error();
    const PixelFormatInfo *format = options.pixelFormat;
    if (!(options.fps > 0.0 && options.fps <= 1000.0))
        return makeError(ErrorCode::InvalidArgument,
                         "synthetic fps must be in (0, 1000] (got " + std::to_string(options.fps) + ")");
    StreamFormat stream{format,     options.width, options.height, 0, options.colorimetry.value_or(Colorimetry{}),
                        options.fps};
    if (auto layout = makeFrameLayout(*format, stream.width, stream.height); !layout)
        return layout.error();
    return std::unique_ptr<FrameSource>(std::make_unique<SyntheticSource>(options, sceneCamera, stream));
}

} // namespace overlayd
