// SPDX-License-Identifier: Apache-2.0
// The shared CameraManager and camera lookup.
#include "drivers/libcamera/camera_manager.h"

#include <cstdlib>
#include <cstring>
#include <mutex>

#include <libcamera/logging.h>
#include <libcamera/property_ids.h>

#include "drivers/libcamera/camera_presence.h"

namespace overlayd {

namespace {

// `mutex` also covers a manager's stop and deletion (its deleter), so that a new manager is never created while the
// last one is still being deleted: libcamera aborts at a second CameraManager. A shared_ptr to a manager is never
// dropped while `mutex` is held (it may be the last one; its deleter takes the mutex).
struct SharedManager {
    std::mutex mutex;
    std::weak_ptr<libcamera::CameraManager> manager;
    bool retired = false;
};

SharedManager &sharedManager()
{
    static auto *shared = new SharedManager; // never destroyed: a manager may be let go during exit
    return *shared;
}

} // namespace

void retireCameraManager()
{
    SharedManager &shared = sharedManager();
    std::lock_guard lock(shared.mutex);
    shared.retired = !shared.manager.expired();
}

Result<std::shared_ptr<libcamera::CameraManager>> cameraManager()
{
    SharedManager &shared = sharedManager();
    std::shared_ptr<libcamera::CameraManager> manager;
    std::unique_lock lock(shared.mutex);
    manager = shared.manager.lock();
    if (manager && !shared.retired)
        return manager;
    if (manager) {
        lock.unlock();
        manager.reset(); // outside the lock: it may be the last holder
        return makeError(ErrorCode::DeviceLost, "libcamera's previous camera manager is still held (a frame of the "
                                                "stopped camera is still out); a fresh one starts once it is let go");
    }
    shared.retired = false;
    // libcamera logs every start (and every configure) at INFO on stderr, in its "Camera" category; a retry starts a
    // manager every few seconds. logSetLevel() matches an existing category by its exact name (0.3.2: "*" matches
    // none, and a category exists once first used), so it is set again after the start: the process's first start
    // is logged, later ones are not. libcamera's own LIBCAMERA_LOG_LEVELS still wins when a user sets it.
    const bool quiet = !std::getenv("LIBCAMERA_LOG_LEVELS");
    if (quiet)
        libcamera::logSetLevel("Camera", "WARN");
    // Stopped before it is deleted, as libcamera asks; under the mutex (see SharedManager).
    manager.reset(new libcamera::CameraManager, [](libcamera::CameraManager *m) {
        std::lock_guard deleting(sharedManager().mutex);
        m->stop();
        delete m;
    });
    if (const int r = manager->start(); r < 0) {
        lock.unlock();
        manager.reset();
        return makeError(ErrorCode::Io, std::string("starting libcamera's camera manager: ") + std::strerror(-r));
    }
    if (quiet)
        libcamera::logSetLevel("Camera", "WARN");
    shared.manager = manager;
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
    std::vector<CameraIdentity> present;
    for (const auto &camera : cameras)
        present.push_back({camera->id(), cameraModel(*camera)});
    if (const auto chosen = matchCameraSpec(spec, present))
        return cameras[*chosen];
    std::string known;
    for (size_t i = 0; i < cameras.size(); ++i)
        known += (i ? ", " : "") + std::to_string(i) + ": '" + present[i].model + "' (" + present[i].id + ")";
    return makeError(ErrorCode::NotFound,
                     "no libcamera camera matches \"" + spec + "\"" +
                         (cameras.empty() ? " (libcamera sees no camera)" : "; there are " + known));
}

} // namespace overlayd
