// SPDX-License-Identifier: Apache-2.0
// The shared CameraManager and camera lookup.
#include "drivers/libcamera/camera_manager.h"

#include <cstdlib>
#include <cstring>
#include <mutex>

#include <libcamera/logging.h>
#include <libcamera/property_ids.h>

namespace overlayd {

Result<std::shared_ptr<libcamera::CameraManager>> cameraManager()
{
    static std::mutex mutex;
    static std::weak_ptr<libcamera::CameraManager> shared;
    std::lock_guard lock(mutex);
    if (auto manager = shared.lock())
        return manager;
    // libcamera logs every start at INFO on stderr; its own LIBCAMERA_LOG_LEVELS still wins when a user sets it.
    if (!std::getenv("LIBCAMERA_LOG_LEVELS"))
        libcamera::logSetLevel("*", "WARN");
    // Stopped before it is deleted, as libcamera asks.
    std::shared_ptr<libcamera::CameraManager> manager(new libcamera::CameraManager, [](libcamera::CameraManager *m) {
        m->stop();
        delete m;
    });
    if (const int r = manager->start(); r < 0)
        return makeError(ErrorCode::Io, std::string("starting libcamera's camera manager: ") + std::strerror(-r));
    shared = manager;
    return manager;
}

std::string cameraModel(const libcamera::Camera &camera)
{
    const auto model = camera.properties().get(libcamera::properties::Model);
    return model ? *model : camera.id();
}

Result<std::shared_ptr<libcamera::Camera>> findCamera(const libcamera::CameraManager &manager, const std::string &spec)
{
    const auto cameras = manager.cameras();
    const bool isIndex = !spec.empty() && spec.size() < 4 && spec.find_first_not_of("0123456789") == std::string::npos;
    if (isIndex && std::stoul(spec) < cameras.size())
        return cameras[std::stoul(spec)];
    for (const auto &camera : cameras) {
        if (camera->id() == spec)
            return camera;
    }
    for (const auto &camera : cameras) {
        if (!isIndex && cameraModel(*camera).find(spec) != std::string::npos)
            return camera;
    }
    std::string known;
    for (size_t i = 0; i < cameras.size(); ++i)
        known +=
            (i ? ", " : "") + std::to_string(i) + ": '" + cameraModel(*cameras[i]) + "' (" + cameras[i]->id() + ")";
    return makeError(ErrorCode::NotFound,
                     "no libcamera camera matches \"" + spec + "\"" +
                         (cameras.empty() ? " (libcamera sees no camera)" : "; there are " + known));
}

} // namespace overlayd
