// SPDX-License-Identifier: Apache-2.0
// Builds without libcamera: the kind is refused with the reason, and the registry is empty.
#include "drivers/libcamera/libcamera_factory.h"

namespace overlayd {

bool libcameraBuiltIn()
{
    return false;
}

std::vector<std::string> libcameraControlNames()
{
    return {};
}

std::optional<ControlValueKind> libcameraControlKind(const std::string &)
{
    return std::nullopt;
}

std::string libcameraControlProblem(const ControlSetting &)
{
    return {};
}

Result<std::unique_ptr<FrameSource>> makeLibcameraSource(const SourceOptions &)
{
    return makeError(
        ErrorCode::Unsupported,
        "this overlayd was built without libcamera (CMake option OVERLAYD_LIBCAMERA): kind = \"libcamera\" "
        "is not available");
}

std::vector<CameraDescription> listLibcameraCameras()
{
    return {};
}

} // namespace overlayd
