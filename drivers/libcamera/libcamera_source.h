// SPDX-License-Identifier: Apache-2.0
// LibcameraSource: a libcamera camera as a FrameSource (negotiation, controls, in-place leases, unplug).
#pragma once

#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>
#include <libcamera/framebuffer_allocator.h>
#include <libcamera/request.h>

#include "base/unique_fd.h"
#include "drivers/frame_source.h"
#include "drivers/libcamera/mapped_frame_buffer.h"
#include "drivers/libcamera/request_recycler.h"
#include "drivers/source_options.h"
#include "media/sequence_counter.h"

namespace overlayd {

using LogFunction = std::function<void(const std::string &)>;

// What the leases share with the source: the camera, its buffers and requests stay alive (and the camera
// acquired) until the last lease is given back, so a zero-copy sink may hold a frame past stop().
struct CameraSession {
    std::shared_ptr<libcamera::CameraManager> manager;
    std::shared_ptr<libcamera::Camera> camera;
    std::unique_ptr<libcamera::FrameBufferAllocator> allocator;
    std::vector<std::unique_ptr<libcamera::Request>> requests;
    std::vector<MappedFrameBuffer> buffers; // by request index
    std::unique_ptr<RequestRecycler> recycler;
    bool acquired = false, running = false;

    ~CameraSession();
};

class LibcameraSource final : public FrameSource
{
public:
    LibcameraSource(SourceOptions options, LogFunction log);
    ~LibcameraSource() override;

    Result<StreamFormat> start() override;
    // Stops the camera: requests in flight complete as cancelled; leases still out become no-ops when given back.
    // A camera that stopped answering is parked instead (see parkIfUnanswering).
    void stop() override;
    // An eventfd (semaphore mode) counting completed requests, written on libcamera's thread.
    int eventFd() const override { return completions_.get(); }
    Result<FrameLease> nextFrame() override;
    std::string describe() const override;

    uint64_t droppedFrames() const { return dropped_; }
    const std::string &adjustment() const { return adjustment_; }

private:
    Result<StreamFormat> configure();
    Status allocate(const libcamera::Stream &stream);
    Status startCamera();
    std::string offered(const libcamera::StreamConfiguration &config) const;
    // libcamera's thread: only the queue, the flag and the eventfd are touched there.
    void onRequestCompleted(libcamera::Request *request);
    void onCameraRemoved(std::shared_ptr<libcamera::Camera> camera);
    void signal();
    // libcamera 0.0.3 aborts the process in Camera::stop() when the device vanished without libcamera noticing
    // (STREAMOFF fails, its requests never complete, PipelineHandler::stop asserts). A camera that has not completed
    // a request for a while is therefore never stopped: it is parked for the life of the process, and the source
    // reports it as lost. True when it parked.
    bool parkIfUnanswering();

    SourceOptions options_;
    LogFunction log_;
    UniqueFd completions_;
    std::shared_ptr<CameraSession> session_;
    libcamera::Stream *stream_ = nullptr;
    StreamFormat format_{};
    std::string name_;

    std::mutex mutex_; // guards completed_, lost_, cameraId_ and lastCompletion_ against libcamera's thread
    std::string cameraId_;
    std::chrono::steady_clock::time_point lastCompletion_{};
    std::deque<unsigned> completed_;
    bool lost_ = false;
    // A callback on libcamera's thread failed (an exception cannot cross into libcamera): the loop then treats the
    // camera as lost and starts it again.
    std::atomic<bool> callbackFailed_{false};

    SequenceCounter sequence_;
    uint64_t dropped_ = 0;
    std::string adjustment_, lastLogged_;
};

} // namespace overlayd
