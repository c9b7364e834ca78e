// SPDX-License-Identifier: Apache-2.0
// ReplaySource: the bookkeeping common to every file-backed source.
#include "drivers/files/replay_base.h"

#include <cmath>

namespace overlayd {

namespace {

constexpr unsigned kPoolFrames = 4;

} // namespace

Result<StreamFormat> ReplaySource::start()
{
    stop();
    auto format = open();
    if (!format)
        return format.error();
    auto pool = FramePool::create(*format, kPoolFrames);
    if (!pool) {
        close();
        return pool.error();
    }
    format_ = *format;
    pool_ = std::move(*pool);
    startWall_ = std::chrono::system_clock::now();
    return format_;
}

void ReplaySource::stop()
{
    close();
    pool_.reset();
    sequence_ = fileIndex_ = 0;
    failure_.reset();
}

std::string ReplaySource::describe() const
{
    return std::string(kind()) + " replay " + options_.replay.path + (options_.replay.loop ? " (looping)" : "");
}

Error ReplaySource::malformed(uint64_t index, const std::string &why) const
{
    return makeError(ErrorCode::Malformed, options_.replay.path + ": frame " + std::to_string(index) + ": " + why);
}

Status ReplaySource::readLooping(FrameBuffer &buffer)
{
    auto status = read(fileIndex_, buffer);
    if (!status && status.error().code == ErrorCode::EndOfStream && options_.replay.loop && fileIndex_ > 0) {
        if (auto rewound = rewind(); !rewound)
            return rewound;
        fileIndex_ = 0;
        status = read(fileIndex_, buffer);
    }
    if (status)
        ++fileIndex_;
    return status;
}

Result<FrameLease> ReplaySource::nextFrame()
{
    if (failure_)
        return *failure_;
    if (!pool_)
        return makeError(ErrorCode::InvalidArgument, describe() + " is not started");
    const auto index = pool_->acquire();
    if (!index)
        return makeError(ErrorCode::TryAgain, "every replay frame is still lent out");
    if (auto status = readLooping(pool_->buffer(*index)); !status) {
        pool_->release(*index);
        if (status.error().code != ErrorCode::EndOfStream)
            failure_ = status.error();
        return status.error();
    }
    FrameMetadata metadata;
    metadata.sequence = sequence_;
    const double fps = format_.fps > 0.0 ? format_.fps : 30.0;
    // The time the frame was made, on CLOCK_MONOTONIC as a camera's is (latency is measured from it); the wall
    // clock the overlay prints advances by the stream's frame period, so a render's text does not depend on speed.
    metadata.timestamp = std::chrono::steady_clock::now().time_since_epoch();
    metadata.wallClock = startWall_ + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                          std::chrono::nanoseconds(std::llround(double(sequence_) * 1e9 / fps)));
    metadata.colorimetry = format_.colorimetry;
    ++sequence_;
    return pool_->lend(*index, metadata);
}

} // namespace overlayd
