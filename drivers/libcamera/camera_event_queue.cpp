// SPDX-License-Identifier: Apache-2.0
// CameraEventQueue: the only work done on libcamera's thread for a removal or an arrival is a push and a wake-up.
#include "drivers/libcamera/camera_event_queue.h"

#include <utility>

namespace overlayd {

void CameraEventQueue::post(CameraEvent::Kind kind, const std::string &cameraId, const std::string &model) noexcept
{
    try {
        std::lock_guard lock(mutex_);
        events_.push_back({kind, cameraId, model});
    } catch (...) {
        overflow_ = true;
    }
    if (wake_)
        wake_();
}

std::vector<CameraEvent> CameraEventQueue::take()
{
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
}

} // namespace overlayd