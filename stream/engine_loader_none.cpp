// SPDX-License-Identifier: Apache-2.0
// Built without the encoded outputs (OVERLAYD_STREAM=OFF, or GStreamer missing): the config refuses them.
#include "stream/engine_loader.h"

namespace overlayd {

bool streamBuiltIn()
{
    return false;
}

Result<std::unique_ptr<EncodedStreamEngine>> loadStreamEngine(const StreamOptions &, const EngineLog &)
{
    return makeError(ErrorCode::Unsupported, "this overlayd was built without the encoded outputs "
                                             "(CMake option OVERLAYD_STREAM, GStreamer)");
}

Status checkEncoder(const EncoderOptions &)
{
    return Ok{}; // the config refuses [encoder] itself
}

Status checkRtspsCertificate(const std::string &, const std::string &)
{
    return Ok{}; // the config refuses RTSP sinks themselves
}

void requireStreamModule() {} // the config refuses [encoder] itself

} // namespace overlayd
