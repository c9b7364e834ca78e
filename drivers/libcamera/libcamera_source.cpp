// SPDX-License-Identifier: Apache-2.0
// LibcameraSource: finding the camera, negotiating its stream, allocating and mapping buffers, starting and stopping;
// then completed requests handed from libcamera's thread to the loop, lent as in-place frames.
#include "drivers/libcamera/libcamera_source.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <libcamera/control_ids.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include "drivers/libcamera/camera_manager.h"
#include "drivers/libcamera/libcamera_controls.h"
#include "drivers/libcamera/libcamera_formats.h"

namespace overlayd {

namespace {

libcamera::StreamRole roleOf(StreamRole role)
{
    switch (role) {
    case StreamRole::Viewfinder:
        return libcamera::StreamRole::Viewfinder;
    case StreamRole::StillCapture:
        return libcamera::StreamRole::StillCapture;
    case StreamRole::VideoRecording:
        break;
    }
    return libcamera::StreamRole::VideoRecording;
}

libcamera::Transform transformOf(ImageTransform transform)
{
    switch (transform) {
    case ImageTransform::HFlip:
        return libcamera::Transform::HFlip;
    case ImageTransform::VFlip:
        return libcamera::Transform::VFlip;
    case ImageTransform::Rot180:
        return libcamera::Transform::Rot180;
    case ImageTransform::Identity:
        break;
    }
    return libcamera::Transform::Identity;
}

Colorimetry colorimetryOf(const std::optional<libcamera::ColorSpace> &space, const PixelFormatInfo &format)
{
    Colorimetry out;
    if (!space)
        return out;
    if (space->ycbcrEncoding == libcamera::ColorSpace::YcbcrEncoding::Rec709)
        out.matrix = YcbcrMatrix::Bt709;
    out.range = space->range == libcamera::ColorSpace::Range::Full ? ColourRange::Full : ColourRange::Limited;
    if (format.encoding == ColourEncoding::Rgb)
        out.range = ColourRange::Full;
    return out;
}

std::string describeStream(const std::string &format, unsigned width, unsigned height)
{
    return std::to_string(width) + "x" + std::to_string(height) + " " + format;
}

} // namespace

CameraSession::~CameraSession()
{
    // libcamera's order: stop, free requests and buffers, then release the camera.
    if (running && camera)
        camera->stop();
    requests.clear();
    buffers.clear();
    allocator.reset();
    if (acquired && camera)
        camera->release();
}

LibcameraSource::LibcameraSource(SourceOptions options, LogFunction log)
    : options_(std::move(options)), log_(std::move(log)),
      completions_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK | EFD_SEMAPHORE))
{}

LibcameraSource::~LibcameraSource()
{
    stop();
}

std::string LibcameraSource::describe() const
{
    return name_.empty() ? "libcamera camera \"" + options_.libcamera.camera + "\"" : name_;
}

Result<StreamFormat> LibcameraSource::start()
{
    stop();
    if (!completions_.isValid())
        return makeError(ErrorCode::Io, std::string("eventfd: ") + std::strerror(errno));
    auto manager = cameraManager();
    if (!manager)
        return manager.error();
    auto session = std::make_shared<CameraSession>();
    session->manager = *manager;
    auto camera = findCamera(*session->manager, options_.libcamera.camera);
    if (!camera)
        return camera.error();
    session->camera = *camera;
    name_ = "libcamera '" + cameraModel(**camera) + "' (" + (*camera)->id() + ")";
    if (const int r = session->camera->acquire(); r < 0)
        return makeError(ErrorCode::DeviceLost,
                         describe() + ": acquire failed: " + std::strerror(-r) + " (another program has it?)");
    session->acquired = true;
    session_ = std::move(session);
    {
        std::lock_guard lock(mutex_);
        completed_.clear();
        lost_ = false;
        cameraId_ = (*camera)->id();
        lastCompletion_ = std::chrono::steady_clock::now(); // the first frame gets the same grace as any other
    }
    sequence_.restart();
    auto format = configure();
    if (!format) {
        stop();
        return format.error();
    }
    if (auto started = startCamera(); !started) {
        stop();
        return started.error();
    }
    return format;
}

std::string LibcameraSource::offered(const libcamera::StreamConfiguration &config) const
{
    std::string out;
    for (const libcamera::PixelFormat &format : config.formats().pixelformats()) {
        out += (out.empty() ? "" : ", ") + formatName(format);
        if (!fromLibcamera(format))
            out += " (not supported by overlayd)";
        else
            out += " " + config.formats().range(format).toString();
    }
    return out.empty() ? "nothing" : out;
}

Result<StreamFormat> LibcameraSource::configure()
{
    libcamera::Camera &camera = *session_->camera;
    const PixelFormatInfo &asked = *options_.pixelFormat;
    const auto wanted = toLibcamera(asked);
    auto config = camera.generateConfiguration({roleOf(options_.libcamera.role)});
    if (!config || config->size() != 1)
        return makeError(ErrorCode::Unsupported, describe() + " has no stream for the asked role");
    libcamera::StreamConfiguration &stream = config->at(0);
    if (!wanted)
        return makeError(ErrorCode::Unsupported, describe() + ": " + std::string(asked.name) +
                                                     " has no libcamera equivalent; the camera offers " +
                                                     offered(stream));
    stream.pixelFormat = *wanted;
    stream.size = {options_.width, options_.height};
    stream.bufferCount = options_.libcamera.bufferCount;
    config->transform = transformOf(options_.libcamera.transform);

    const auto status = config->validate();
    if (status == libcamera::CameraConfiguration::Invalid)
        return makeError(ErrorCode::Unsupported,
                         describe() + " refuses " +
                             describeStream(std::string(asked.name), options_.width, options_.height) + "; it offers " +
                             offered(stream));
    const PixelFormatInfo *got = fromLibcamera(stream.pixelFormat);
    if (!got)
        return makeError(ErrorCode::Unsupported, describe() + " would give " + formatName(stream.pixelFormat) +
                                                     ", which overlayd cannot blend into; it offers " +
                                                     offered(stream));
    adjustment_.clear();
    if (status == libcamera::CameraConfiguration::Adjusted) {
        adjustment_ = "asked " + describeStream(std::string(asked.name), options_.width, options_.height) + ", got " +
                      describeStream(std::string(got->name), stream.size.width, stream.size.height);
        if (config->transform != transformOf(options_.libcamera.transform))
            adjustment_ += std::string(" (transform ") + transformToString(config->transform) + " instead of " +
                           transformToString(transformOf(options_.libcamera.transform)) + ")";
        if (adjustment_ != lastLogged_ && log_)
            log_(describe() + ": " + adjustment_);
        lastLogged_ = adjustment_;
    }
    if (const int r = camera.configure(config.get()); r < 0)
        return makeError(ErrorCode::DeviceLost, describe() + ": configure failed: " + std::strerror(-r));
    stream_ = stream.stream();

    format_ = StreamFormat{};
    format_.format = got;
    format_.width = stream.size.width;
    format_.height = stream.size.height;
    format_.stride = stream.stride;
    format_.colorimetry = options_.colorimetry.value_or(colorimetryOf(stream.colorSpace, *got));
    format_.fps = options_.fps;
    if (auto allocated = allocate(*stream_); !allocated)
        return allocated.error();
    format_.dmabufBuffers = unsigned(session_->buffers.size());
    return format_;
}

Status LibcameraSource::allocate(const libcamera::Stream &stream)
{
    CameraSession &session = *session_;
    session.allocator = std::make_unique<libcamera::FrameBufferAllocator>(session.camera);
    auto *mutableStream = const_cast<libcamera::Stream *>(&stream);
    if (const int r = session.allocator->allocate(mutableStream); r < 0)
        return makeError(ErrorCode::Io, describe() + ": allocating buffers failed: " + std::strerror(-r));
    const auto &buffers = session.allocator->buffers(mutableStream);
    if (buffers.size() < 2)
        return makeError(ErrorCode::Unsupported, describe() + " gave " + std::to_string(buffers.size()) + " buffers");
    for (size_t i = 0; i < buffers.size(); ++i) {
        auto mapped =
            MappedFrameBuffer::map(*buffers[i], *format_.format, format_.width, format_.height, format_.stride);
        if (!mapped)
            return makeError(mapped.error().code,
                             describe() + ": buffer " + std::to_string(i) + ": " + mapped.error().message);
        session.buffers.push_back(std::move(*mapped));
        auto request = session.camera->createRequest(i);
        if (!request || request->addBuffer(mutableStream, buffers[i].get()) < 0)
            return makeError(ErrorCode::Io, describe() + ": could not make a request for buffer " + std::to_string(i));
        session.requests.push_back(std::move(request));
    }
    // The give-back (any thread): end CPU access, then the request goes back to the camera with its buffer.
    std::weak_ptr<CameraSession> weak = session_;
    session.recycler = std::make_unique<RequestRecycler>([weak](unsigned index) {
        const auto s = weak.lock();
        if (!s || index >= s->requests.size())
            return 0;
        s->buffers[index].endCpuAccess();
        s->requests[index]->reuse(libcamera::Request::ReuseBuffers);
        return s->camera->queueRequest(s->requests[index].get());
    });
    return Ok{};
}

Status LibcameraSource::startCamera()
{
    CameraSession &session = *session_;
    auto controls = buildControls(options_.libcamera.controls, session.camera->controls());
    if (!controls)
        return controls.error();
    // The asked frame rate, when the camera lets it be set and the config did not set the limits itself.
    const auto &limits = libcamera::controls::FrameDurationLimits;
    if (options_.fps > 0 && session.camera->controls().count(limits.id()) && !controls->contains(limits.id())) {
        const int64_t frameUs = std::llround(1e6 / options_.fps);
        controls->set(limits, {frameUs, frameUs});
    }
    session.camera->requestCompleted.connect(this, &LibcameraSource::onRequestCompleted);
    session.manager->cameraRemoved.connect(this, &LibcameraSource::onCameraRemoved);
    if (const int r = session.camera->start(&*controls); r < 0)
        return makeError(ErrorCode::DeviceLost, describe() + ": start failed: " + std::strerror(-r));
    session.running = true;
    for (auto &request : session.requests) {
        if (const int r = session.camera->queueRequest(request.get()); r < 0)
            return makeError(ErrorCode::DeviceLost, describe() + ": queueing a request failed: " + std::strerror(-r));
    }
    return Ok{};
}

bool LibcameraSource::parkIfUnanswering()
{
    // Three frame times, and at least a second: a camera that is merely slow is stopped as usual.
    const auto silence = std::max<std::chrono::steady_clock::duration>(
        std::chrono::seconds(1), std::chrono::milliseconds(int64_t(3000.0 / std::max(options_.fps, 0.1))));
    {
        std::lock_guard lock(mutex_);
        if (!session_->running || lost_ || std::chrono::steady_clock::now() - lastCompletion_ < silence)
            return false;
    }
    // Never destroyed: destroying the camera would stop it (and abort); the manager stays with it, so a later
    // start() finds the same camera and is told it is busy, and the daemon keeps showing NO SIGNAL.
    static auto *parked = new std::vector<std::shared_ptr<CameraSession>>;
    parked->push_back(session_);
    if (log_)
        log_(describe() + " stopped answering: it is left as it is (libcamera 0.0.3 aborts when asked to stop a "
                          "camera whose device vanished unnoticed); restart overlayd to use it again");
    return true;
}

void LibcameraSource::stop()
{
    if (!session_)
        return;
    if (session_->recycler)
        session_->recycler->detach();
    if (session_->running && parkIfUnanswering()) {
        session_->camera->requestCompleted.disconnect(this);
        session_->manager->cameraRemoved.disconnect(this);
        session_.reset();
        std::lock_guard lock(mutex_);
        completed_.clear();
        return;
    }
    if (session_->running) {
        session_->camera->stop();
        session_->running = false;
    }
    session_->camera->requestCompleted.disconnect(this);
    session_->manager->cameraRemoved.disconnect(this);
    session_.reset(); // the camera is released when the last lease is given back
    std::lock_guard lock(mutex_);
    completed_.clear();
    uint64_t drained;
    while (::read(completions_.get(), &drained, sizeof(drained)) > 0) {
    }
}

// LibcameraSource: completed requests handed from libcamera's thread to the loop, lent as in-place frames.

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
        lastCompletion_ = std::chrono::steady_clock::now();
    } catch (...) {
        callbackFailed_ = true; // a completion lost (out of memory): the loop restarts the camera
    }
    signal();
}

void LibcameraSource::onCameraRemoved(std::shared_ptr<libcamera::Camera> camera)
{
    try {
        std::lock_guard lock(mutex_);
        if (camera->id() != cameraId_)
            return;
        lost_ = true;
    } catch (...) {
        callbackFailed_ = true;
    }
    signal();
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
    unsigned index = 0;
    {
        std::lock_guard lock(mutex_);
        if (lost_)
            return makeError(ErrorCode::DeviceLost, describe() + " was removed");
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
