// LibcameraSource: completed requests handed from libcamera's thread to the loop, lent as in-place frames.
#include "drivers/libcamera/libcamera_source.h"

#include <unistd.h>

#include "drivers/libcamera/camera_manager.h"

#include <libcamera/control_ids.h>

namespace overlayd {

void LibcameraSource::signal()
{
    const uint64_t one = 1;
    // A full counter (2^64 - 2 unread completions) cannot happen: every completion is read once.
    (void)!::write(completions_.get(), &one, sizeof(one));
}

void LibcameraSource::onRequestCompleted(libcamera::Request *request)
{
    try {
        std::lock_guard lock(mutex_);
        completed_.push_back(unsigned(request->cookie()));
    } catch (...) {
        callbackFailed_ = true; // a completion lost (out of memory): the loop restarts the camera
    }
    signal();
}

void LibcameraSource::onDisconnected()
{
    events_.post(CameraEvent::Kind::Disconnected, {});
}

void LibcameraSource::onCameraRemoved(std::shared_ptr<libcamera::Camera> camera)
{
    events_.post(CameraEvent::Kind::Removed, camera->id());
}

void LibcameraSource::onCameraAdded(std::shared_ptr<libcamera::Camera> camera)
{
    std::string model;
    try {
        model = cameraModel(*camera);
    } catch (...) {
        // the model only helps matching by model; the id is posted without it
    }
    events_.post(CameraEvent::Kind::Added, camera->id(), model);
}

bool LibcameraSource::takeEvents()
{
    if (events_.takeOverflow())
        callbackFailed_ = true;
    for (const CameraEvent &event : events_.take()) {
        const bool wasLost = presence_.lost();
        presence_.apply(event);
        if (!wasLost && presence_.lost() && log_)
            log_(describe() + (event.kind == CameraEvent::Kind::Disconnected ? " was disconnected" : " was removed") +
                 ": waiting for it to come back");
    }
    return presence_.lost();
}

Result<FrameLease> LibcameraSource::nextFrame()
{
    if (!session_ || !session_->running)
        return makeError(ErrorCode::DeviceLost, describe() + " is not streaming");
    if (auto failed = session_->recycler->takeError())
        return *failed;
    if (callbackFailed_.exchange(false))
        return makeError(ErrorCode::DeviceLost, describe() + ": a libcamera callback failed (out of memory?)");
    uint64_t one;
    const bool woken = ::read(completions_.get(), &one, sizeof(one)) == sizeof(one);
    if (takeEvents())
        return makeError(ErrorCode::DeviceLost, describe() + " was unplugged");
    if (removal_.takeRemoval(devices_))
        return makeError(ErrorCode::DeviceLost, describe() + " was unplugged (its device node went away)");
    unsigned index = 0;
    {
        std::lock_guard lock(mutex_);
        if (!woken || completed_.empty())
            return makeError(ErrorCode::TryAgain, describe() + ": no frame ready");
        index = completed_.front();
        completed_.pop_front();
    }
    CameraSession &session = *session_;
    if (index >= session.requests.size())
        return makeError(ErrorCode::TryAgain, describe() + ": a request that is not ours");
    libcamera::Request &request = *session.requests[index];
    if (request.status() == libcamera::Request::RequestCancelled)
        return makeError(ErrorCode::DeviceLost, describe() + ": the camera cancelled a request");
    const libcamera::FrameBuffer *buffer = request.buffers().begin()->second;
    const libcamera::FrameMetadata &bufferMetadata = buffer->metadata();
    if (bufferMetadata.status != libcamera::FrameMetadata::FrameSuccess) {
        ++dropped_;
        session.recycler->lend();
        session.recycler->giveBack(index);
        return makeError(ErrorCode::TryAgain, describe() + ": frame marked failed by the camera");
    }

    dropped_ += sequence_.advance(bufferMetadata.sequence);

    FrameMetadata metadata;
    metadata.sequence = sequence_.relative(bufferMetadata.sequence);
    const auto sensorTime = request.metadata().get(libcamera::controls::SensorTimestamp);
    metadata.timestamp = std::chrono::nanoseconds(sensorTime ? uint64_t(*sensorTime) : bufferMetadata.timestamp);
    metadata.wallClock = std::chrono::system_clock::now();
    metadata.colorimetry = format_.colorimetry;
    if (const auto exposure = request.metadata().get(libcamera::controls::ExposureTime))
        metadata.exposureUs = *exposure;
    if (const auto gain = request.metadata().get(libcamera::controls::AnalogueGain))
        metadata.analogueGain = *gain;

    const MappedFrameBuffer &mapped = session.buffers[index];
    mapped.beginCpuAccess();
    session.recycler->lend();
    // The lease keeps the session alive and gives the request back through its recycler (aliasing: no allocation).
    return FrameLease(mapped.view(), metadata, std::shared_ptr<LeaseOwner>(session_, session_->recycler.get()), index);
}

} // namespace overlayd