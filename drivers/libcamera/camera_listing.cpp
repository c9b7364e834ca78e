// SPDX-License-Identifier: Apache-2.0
// list-cameras for libcamera: each camera's id, model, and what its video stream offers.
#include <libcamera/stream.h>

#include "drivers/camera_list.h"
#include "drivers/libcamera/camera_manager.h"
#include "drivers/libcamera/libcamera_formats.h"

namespace overlayd {

std::vector<CameraDescription> listLibcameraCameras()
{
    std::vector<CameraDescription> out;
    auto manager = cameraManager();
    if (!manager) {
        out.push_back({"libcamera", "", "", manager.error().message, {}});
        return out;
    }
    for (const auto &camera : (*manager)->cameras()) {
        CameraDescription description{"libcamera", camera->id(), cameraModel(*camera), "", {}};
        // The formats of a stream are known without acquiring the camera (another program may be streaming it).
        const auto config = camera->generateConfiguration({libcamera::StreamRole::VideoRecording});
        if (!config || config->empty()) {
            description.error = "no video stream";
            out.push_back(std::move(description));
            continue;
        }
        const libcamera::StreamFormats &formats = config->at(0).formats();
        for (const libcamera::PixelFormat &format : formats.pixelformats()) {
            CameraMode mode{formatName(format), fromLibcamera(format) != nullptr, {}, {}};
            for (const libcamera::Size &size : formats.sizes(format))
                mode.sizes.push_back(size.toString());
            if (mode.sizes.empty())
                mode.sizes.push_back(formats.range(format).toString());
            description.modes.push_back(std::move(mode));
        }
        out.push_back(std::move(description));
    }
    return out;
}

} // namespace overlayd
