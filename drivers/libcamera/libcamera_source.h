// SPDX-License-Identifier: Apache-2.0
// LibcameraSource: a libcamera camera as a FrameSource (negotiation, controls, in-place leases, unplug).
#pragma once

#include <atomic>
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
#include "drivers/libcamera/camera_event_queue.h"
#include "drivers/libcamera/camera_presence.h"
#include "drivers/libcamera/device_removal_watch.h"
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
    // Set on libcamera's thread by Camera::disconnected; libcamera then refuses stop() and release() (-ENODEV).
    std::atomic<bool> disconnected{false};

    ~CameraSession();
};

class LibcameraSource final : public FrameSource
{
public:
    LibcameraSource(SourceOptions options, LogFunction log);
    ~LibcameraSource() override;

    Result<StreamFormat> start() override;
    // Stops the camera, also one whose device vanished (see vanished_device_ioctl.h): requests in flight complete as
    // cancelled; leases still out become no-ops when given back. The camera manager is retired: the next start()
    // enumerates afresh (see retireCameraManager).
    void stop() override;
    // Readable when a request completed or a camera event came (an eventfd in semaphore mode, written on
    // libcamera's thread) or a kernel uevent came (the removal watch): an epoll set of both.
    int eventFd() const override { return poller_.isValid() ? poller_.get() : completions_.get(); }
    Result<FrameLease> nextFrame() override;
    std::string describe() const override;

    uint64_t droppedFrames() const { return dropped_; }
    const std::string &adjustment() const { return adjustment_; }

private:
    Result<StreamFormat> configure();
    Status allocate(const libcamera::Stream &stream);
    Status startCamera();
    std::string offered(const libcamera::StreamConfiguration &config) const;
    Result<std::shared_ptr<libcamera::Camera>> chooseCamera(const libcamera::CameraManager &manager);
    // libcamera's thread: only the queues and the eventfd are touched there.
    void onRequestCompleted(libcamera::Request *request);
    void onDisconnected();
    void onCameraRemoved(std::shared_ptr<libcamera::Camera> camera);
    void onCameraAdded(std::shared_ptr<libcamera::Camera> camera);
    void signal();
    // The loop: applies the handed-over camera events; true when the open camera is gone.
    bool takeEvents();

    SourceOptions options_;
    LogFunction log_;
    UniqueFd completions_;
    DeviceRemovalWatch removal_;
    UniqueFd poller_;
    std::vector<dev_t> devices_; // the open camera's device nodes (libcamera's SystemDevices)
    std::shared_ptr<CameraSession> session_;
    libcamera::Stream *stream_ = nullptr;
    StreamFormat format_{};
    std::string name_;

    std::mutex mutex_; // guards completed_ against libcamera's thread
    std::deque<unsigned> completed_;
    CameraEventQueue events_;
    CameraPresence presence_; // the loop's only
    // A callback on libcamera's thread failed (an exception cannot cross into libcamera): the loop then treats the
    // camera as lost and starts it again.
    std::atomic<bool> callbackFailed_{false};

    SequenceCounter sequence_;
    uint64_t dropped_ = 0;
    std::string adjustment_, lastLogged_;
};

} // namespace overlayd
