// CameraSpec::build: placeholder until the config loader lands.
#include "config/camera_spec.h"

namespace overlayd {

Result<Camera> CameraSpec::build(unsigned, unsigned) const
{
    return makeError(ErrorCode::Unsupported, "camera configuration is not implemented yet");
}

} // namespace overlayd
