// SPDX-License-Identifier: Apache-2.0
// The process's one libcamera CameraManager (libcamera refuses a second), and finding the configured camera in it.
#pragma once

#include <memory>
#include <string>

#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>

#include "base/result.h"

namespace overlayd {

// Started on first use and stopped when the last holder lets go: a source that retries after its camera vanished
// gets a fresh enumeration (without udevd, libcamera sees no hot-plug events, so re-enumerating is how a camera
// that came back is found). A retired manager is not handed out again: while a holder keeps it, this fails
// (DeviceLost) and the caller retries later.
Result<std::shared_ptr<libcamera::CameraManager>> cameraManager();

// The manager running now may list a camera whose device is gone: libcamera 0.3.2 removes a camera only when its
// pipeline handler reports the unplug (uvcvideo alone does), and a manager that still lists it aborts the process
// when the device comes back (CameraManager::Private::addCamera: "Trying to register a camera with a duplicated
// ID" is fatal). Called when a source stops its camera: the next cameraManager() starts a fresh one, once the last
// holder of this one (a frame still out) lets go.
void retireCameraManager();

// `spec`: an index into the manager's list ("0"), a camera id, or a substring of the model name. The error
// lists the cameras there are.
Result<std::shared_ptr<libcamera::Camera>> findCamera(const libcamera::CameraManager &manager, const std::string &spec);

// The sensor's model ("Sensor B"), or the id when the camera names none.
std::string cameraModel(const libcamera::Camera &camera);

} // namespace overlayd
