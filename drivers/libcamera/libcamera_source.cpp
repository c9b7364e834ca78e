// SPDX-License-Identifier: Apache-2.0
// LibcameraSource: finding the camera, negotiating its stream, allocating and mapping buffers, starting and stopping;
// then completed requests handed from libcamera's thread to the loop, lent as in-place frames.
#include "drivers/libcamera/libcamera_source.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <libcamera/control_ids.h>
#include <libcamera/property_ids.h>

#include "drivers/libcamera/camera_manager.h"
#include "drivers/libcamera/libcamera_controls.h"
#include "drivers/libcamera/libcamera_formats.h"
#include "drivers/libcamera/vanished_device_ioctl.h"

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

// The config's transform is relative to the upright image, as libcamera 0.3's orientation is (the pipeline
// compensates the camera's mounting rotation either way): the orientations EXIF names a flip, a mirror and a turn.
libcamera::Orientation orientationOf(ImageTransform transform)
{
    switch (transform) {
    case ImageTransform::HFlip:
        return libcamera::Orientation::Rotate0Mirror;
    case ImageTransform::VFlip:
        return libcamera::Orientation::Rotate180Mirror;
    case ImageTransform::Rot180:
        return libcamera::Orientation::Rotate180;
    case ImageTransform::Identity:
        break;
    }
    return libcamera::Orientation::Rotate0;
}

std::string orientationName(libcamera::Orientation orientation)
{
    std::ostringstream out;
    out << orientation;
    return out.str();
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
    if (camera)
        camera->disconnected.disconnect(this);
    // libcamera's order: stop, free requests and buffers, then release the camera.
    if (running && camera)
        camera->stop();
    requests.clear();
    buffers.clear();
    allocator.reset();
    if (acquired && camera)
        camera->release();
}

namespace {

// The camera each spec last opened, for the life of the process: the daemon makes a new source for every retry
// (SourceSupervisor::open), and CameraPresence's choice of the camera that went away must outlive the source.
struct OpenedCameras {
    std::mutex mutex;
    std::map<std::string, CameraIdentity> bySpec;
};

OpenedCameras &openedCameras()
{
    static auto *opened = new OpenedCameras; // never destroyed: sources may stop during exit
    return *opened;
}

std::optional<CameraIdentity> recallOpened(const std::string &spec)
{
    OpenedCameras &opened = openedCameras();
    std::lock_guard lock(opened.mutex);
    const auto found = opened.bySpec.find(spec);
    return found == opened.bySpec.end() ? std::nullopt : std::optional<CameraIdentity>(found->second);
}

void storeOpened(const std::string &spec, const CameraIdentity &camera)
{
    OpenedCameras &opened = openedCameras();
    std::lock_guard lock(opened.mutex);
    opened.bySpec[spec] = camera;
}

} // namespace

LibcameraSource::LibcameraSource(SourceOptions options, LogFunction log)
    : options_(std::move(options)), log_(std::move(log)),
      completions_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK | EFD_SEMAPHORE)), events_([this] { signal(); }),
      presence_(options_.libcamera.camera)
{
    if (const auto earlier = recallOpened(options_.libcamera.camera))
        presence_.remember(*earlier);
    // One fd for the loop: completions and camera events, and the kernel's device removals.
    if (removal_.fd() >= 0 && completions_.isValid()) {
        poller_ = UniqueFd(::epoll_create1(EPOLL_CLOEXEC));
        for (const int fd : {completions_.get(), removal_.fd()}) {
            epoll_event event{};
            event.events = EPOLLIN;
            event.data.fd = fd;
            if (poller_.isValid() && ::epoll_ctl(poller_.get(), EPOLL_CTL_ADD, fd, &event) < 0)
                poller_.reset();
        }
    }
}

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
    (void)events_.take(); // about a camera this source no longer holds
    auto manager = cameraManager();
    if (!manager)
        return manager.error();
    auto session = std::make_shared<CameraSession>();
    session->manager = *manager;
    auto camera = chooseCamera(*session->manager);
    if (!camera)
        return camera.error();
    session->camera = *camera;
    name_ = "libcamera '" + cameraModel(**camera) + "' (" + (*camera)->id() + ")";
    if (const int r = session->camera->acquire(); r < 0)
        return makeError(ErrorCode::DeviceLost,
                         describe() + ": acquire failed: " + std::strerror(-r) + " (another program has it?)");
    session->acquired = true;
    devices_.clear();
    if (const auto nodes = (*camera)->properties().get(libcamera::properties::SystemDevices))
        for (const int64_t node : *nodes)
            devices_.push_back(dev_t(node));
    session_ = std::move(session);
    const bool again = presence_.remembered().has_value();
    presence_.opened({(*camera)->id(), cameraModel(**camera)});
    storeOpened(options_.libcamera.camera, *presence_.remembered());
    {
        std::lock_guard lock(mutex_);
        completed_.clear();
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
    if (again && log_)
        log_(describe() + " is streaming again");
    return format;
}

Result<std::shared_ptr<libcamera::Camera>> LibcameraSource::chooseCamera(const libcamera::CameraManager &manager)
{
    const auto cameras = manager.cameras();
    std::vector<CameraIdentity> present;
    for (const auto &camera : cameras)
        present.push_back({camera->id(), cameraModel(*camera)});
    if (const auto chosen = presence_.choose(present))
        return cameras[*chosen];
    if (!presence_.remembered())
        return findCamera(manager, options_.libcamera.camera); // its error lists the cameras there are
    return makeError(ErrorCode::DeviceLost, "libcamera camera " + presence_.awaited() + " is not back yet");
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
    const libcamera::Orientation orientation = orientationOf(options_.libcamera.transform);
    config->orientation = orientation;

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
        if (config->orientation != orientation)
            adjustment_ += " (orientation " + orientationName(config->orientation) + " instead of " +
                           orientationName(orientation) + ")";
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
    // The session's own flag (its destructor's guide); the source's slot hands the event over to the loop.
    CameraSession *raw = &session;
    session.camera->disconnected.connect(raw, [raw] { raw->disconnected = true; });
    session.camera->disconnected.connect(this, &LibcameraSource::onDisconnected);
    session.manager->cameraRemoved.connect(this, &LibcameraSource::onCameraRemoved);
    session.manager->cameraAdded.connect(this, &LibcameraSource::onCameraAdded);
    if (const int r = session.camera->start(&*controls); r < 0)
        return makeError(ErrorCode::DeviceLost, describe() + ": start failed: " + std::strerror(-r));
    session.running = true;
    for (auto &request : session.requests) {
        if (const int r = session.camera->queueRequest(request.get()); r < 0)
            return makeError(ErrorCode::DeviceLost, describe() + ": queueing a request failed: " + std::strerror(-r));
    }
    return Ok{};
}

void LibcameraSource::stop()
{
    if (!session_)
        return;
    if (session_->recycler)
        session_->recycler->detach();
    session_->camera->requestCompleted.disconnect(this);
    session_->camera->disconnected.disconnect(this);
    session_->manager->cameraRemoved.disconnect(this);
    session_->manager->cameraAdded.disconnect(this);
    if (session_->running && !session_->disconnected) {
        // A device that vanished unnoticed by libcamera (every pipeline but uvcvideo) answers STREAMOFF and QBUF
        // with ENODEV; the ioctl shim reports them done, so the stop completes instead of asserting.
        const uint64_t vanishedBefore = vanishedDeviceCalls();
        session_->camera->stop();
        session_->running = false;
        if (vanishedDeviceCalls() != vanishedBefore && log_)
            log_(describe() + " was unplugged (its device is gone): stopped, waiting for it to come back");
    }
    // A camera libcamera marked disconnected refuses stop() and release() (-ENODEV): it is dropped as it is
    // (uvcvideo, the only pipeline that reports unplugs in 0.3.2, runs no IPA thread, so destroying it is safe).
    session_.reset(); // the camera is released, and the manager let go, when the last lease is given back
    // The manager may still list the camera that went away; a retry must get a fresh one (see retireCameraManager).
    retireCameraManager();
    presence_.closed();
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
