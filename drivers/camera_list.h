// SPDX-License-Identifier: Apache-2.0
// What `overlayd list-cameras` shows: every camera a source could open, with what each offers.
#pragma once

#include <string>
#include <vector>

namespace overlayd {

struct CameraMode {
    std::string format;             // the project's name ("NV12"), or the API's own for a format overlayd cannot use
    bool usable = false;            // overlayd can blend into it (or decode it: MJPEG)
    std::vector<std::string> sizes; // "640x480", or a range "16x16-1920x1080 (step 2x2)"
    std::vector<double> fps;        // discrete frame rates, when the device lists them
};

struct CameraDescription {
    std::string api;   // "v4l2" or "libcamera"
    std::string id;    // what goes into the config: the device path, or the libcamera camera id
    std::string model; // card name / sensor model
    std::string error; // why it could not be asked (busy, permissions); its modes are then empty
    std::vector<CameraMode> modes;
};

// V4L2 capture devices under /dev (drivers/v4l2/) and libcamera cameras (drivers/libcamera/).
std::vector<CameraDescription> listV4l2Cameras();
std::vector<CameraDescription> listLibcameraCameras();

} // namespace overlayd
