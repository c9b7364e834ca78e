// SPDX-License-Identifier: Apache-2.0
// CameraEventQueue: camera removals and arrivals handed from libcamera's thread to the daemon's loop.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace overlayd {

// What libcamera said about a camera; `cameraId` is libcamera's id ("platform/vimc.0 Sensor B").
struct CameraEvent {
    enum class Kind { Disconnected, Removed, Added };
    Kind kind;
    std::string cameraId, model;
};

// libcamera emits Camera::disconnected and CameraManager::cameraRemoved/cameraAdded on its own thread, where stopping,
// releasing or acquiring a camera deadlocks or crashes (its pipeline handler runs there). Only this queue and the
// wake-up (the source's eventfd) are touched on that thread; the loop takes the events and acts on them. The seam
// is `wake`, so the hand-off is tested without a camera.
class CameraEventQueue
{
public:
    explicit CameraEventQueue(std::function<void()> wake) : wake_(std::move(wake)) {}
    CameraEventQueue(const CameraEventQueue &) = delete;
    CameraEventQueue &operator=(const CameraEventQueue &) = delete;

    // Any thread; never throws (an exception cannot cross into libcamera): an event that cannot be stored is
    // counted, and the loop then treats the camera as lost.
    void post(CameraEvent::Kind kind, const std::string &cameraId, const std::string &model = {}) noexcept;
    // The loop: the events in the order they were posted.
    std::vector<CameraEvent> take();
    // Whether an event was lost since the last call.
    bool takeOverflow() { return overflow_.exchange(false); }

private:
    std::function<void()> wake_;
    std::mutex mutex_;
    std::vector<CameraEvent> events_;
    std::atomic<bool> overflow_{false};
};

} // namespace overlayd