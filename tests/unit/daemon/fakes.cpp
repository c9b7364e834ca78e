// SPDX-License-Identifier: Apache-2.0
// Fakes of the pipeline's stages.
#include "fakes.h"

#include <algorithm>

namespace overlayd::test {

StreamFormat greyFormat(unsigned width, unsigned height, double fps)
{
    StreamFormat format;
    format.format = pixelFormatFromName("GREY");
    format.width = width;
    format.height = height;
    format.fps = fps;
    return format;
}

FakeSource::FakeSource(std::shared_ptr<Shared> shared, StreamFormat format)
    : shared_(std::move(shared)), format_(format)
{}

Result<StreamFormat> FakeSource::start()
{
    ++shared_->starts;
    if (!shared_->startErrors.empty()) {
        Error error = shared_->startErrors.front();
        shared_->startErrors.pop_front();
        return error;
    }
    auto buffer = FrameBuffer::allocate(format_);
    if (!buffer)
        return buffer.error();
    buffer_.emplace(std::move(*buffer));
    started_ = true;
    shared_->mostRunning = std::max(shared_->mostRunning, ++shared_->running);
    return format_;
}

void FakeSource::stop()
{
    ++shared_->stops;
    if (started_)
        --shared_->running;
    started_ = false;
}

Result<FrameLease> FakeSource::nextFrame()
{
    if (!shared_->script.empty()) {
        Error error = shared_->script.front();
        shared_->script.pop_front();
        return error;
    }
    FrameView view = buffer_->view();
    std::fill(buffer_->data(), buffer_->data() + buffer_->size(), uint8_t(0));
    view.planes[0].data[0] = uint8_t(sequence_);
    FrameMetadata metadata;
    metadata.sequence = sequence_++;
    return FrameLease(view, metadata, [] {});
}

void RecordingSink::Shared::setGate(bool open)
{
    std::lock_guard lock(mutex);
    gateOpen = open;
    changed.notify_all();
}

void RecordingSink::Shared::waitEntered(int count)
{
    std::unique_lock lock(mutex);
    changed.wait(lock, [this, count] { return entered >= count; });
}

size_t RecordingSink::Shared::written()
{
    std::lock_guard lock(mutex);
    return firstBytes.size();
}

Status RecordingSink::open(const StreamFormat &)
{
    std::lock_guard lock(shared_->mutex);
    ++shared_->opens;
    if (shared_->failOpens > 0) {
        --shared_->failOpens;
        return makeError(ErrorCode::NotFound, name_ + ": No such file or directory");
    }
    return Ok{};
}

Status RecordingSink::write(const FrameView &frame, const FrameMetadata &metadata)
{
    std::unique_lock lock(shared_->mutex);
    ++shared_->entered;
    shared_->changed.notify_all();
    shared_->changed.wait(lock, [this] { return shared_->gateOpen; });
    shared_->firstBytes.push_back(frame.planes[0].data[0]);
    shared_->lastBytes.push_back(frame.planes[0].data[frame.planes[0].stride * (frame.height - 1) + frame.width - 1]);
    shared_->sequences.push_back(metadata.sequence);
    uint8_t brightest = 0;
    for (unsigned y = 0; y < frame.height; ++y)
        for (unsigned x = 0; x < frame.width; ++x)
            brightest = std::max(brightest, frame.planes[0].data[y * frame.planes[0].stride + x]);
    shared_->maxima.push_back(brightest);
    return Ok{};
}

Status RecordingSink::close()
{
    std::lock_guard lock(shared_->mutex);
    ++shared_->closes;
    return Ok{};
}

Status MarkingRenderer::blend(const FrameView &frame, const FrameMetadata &, double)
{
    frame.planes[0].data[frame.planes[0].stride * (frame.height - 1) + frame.width - 1] = mark_;
    return Ok{};
}

int RecordingNotifier::count(const std::string &event) const
{
    return int(std::count(events.begin(), events.end(), event));
}

std::string RecordingNotifier::lastStatus() const
{
    for (auto it = events.rbegin(); it != events.rend(); ++it)
        if (it->rfind("STATUS=", 0) == 0)
            return it->substr(7);
    return {};
}

} // namespace overlayd::test
