// SPDX-License-Identifier: Apache-2.0
// `overlayd list-cameras`: what a user puts under [source] — each camera's id, model, formats, sizes and rates.
#include <string>

#include "base/json_text.h"
#include "base/number_text.h"
#include "drivers/camera_list.h"
#include "tools/commands.h"

namespace overlayd {

namespace {

std::string numberText(double value)
{
    return shortNumber(value);
}

std::string asJson(const std::vector<CameraDescription> &cameras)
{
    std::string out = "[";
    for (size_t c = 0; c < cameras.size(); ++c) {
        const CameraDescription &camera = cameras[c];
        out += std::string(c ? ",\n " : "\n ") + "{\"api\": " + jsonString(camera.api) +
               ", \"id\": " + jsonString(camera.id) + ", \"model\": " + jsonString(camera.model);
        if (!camera.error.empty())
            out += ", \"error\": " + jsonString(camera.error);
        out += ", \"formats\": [";
        for (size_t m = 0; m < camera.modes.size(); ++m) {
            const CameraMode &mode = camera.modes[m];
            out += std::string(m ? ", " : "") + "{\"format\": " + jsonString(mode.format) +
                   ", \"usable\": " + (mode.usable ? "true" : "false") + ", \"sizes\": [";
            for (size_t s = 0; s < mode.sizes.size(); ++s)
                out += (s ? ", " : "") + jsonString(mode.sizes[s]);
            out += "], \"fps\": [";
            for (size_t f = 0; f < mode.fps.size(); ++f)
                out += (f ? ", " : "") + numberText(mode.fps[f]);
            out += "]}";
        }
        out += "]}";
    }
    return out + (cameras.empty() ? "]\n" : "\n]\n");
}

std::string asText(const std::vector<CameraDescription> &cameras)
{
    if (cameras.empty())
        return "no cameras found (V4L2 capture devices under /dev, libcamera cameras)\n";
    std::string out;
    for (const CameraDescription &camera : cameras) {
        out += camera.api + " " + camera.id + " '" + camera.model + "'";
        out += camera.error.empty() ? "\n" : ": " + camera.error + "\n";
        for (const CameraMode &mode : camera.modes) {
            out += "  " + mode.format + (mode.usable ? "" : " (overlayd cannot use it)") + ":";
            for (const std::string &size : mode.sizes)
                out += " " + size;
            if (!mode.fps.empty()) {
                out += " @";
                for (const double fps : mode.fps)
                    out += " " + numberText(fps);
                out += " fps (first size)";
            }
            out += "\n";
        }
    }
    return out;
}

} // namespace

int listCamerasCommand(bool json)
{
    std::vector<CameraDescription> cameras = listV4l2Cameras();
    for (CameraDescription &camera : listLibcameraCameras())
        cameras.push_back(std::move(camera));
    const std::string output = json ? asJson(cameras) : asText(cameras);
    std::fwrite(output.data(), 1, output.size(), stdout);
    return kExitOk;
}

} // namespace overlayd
