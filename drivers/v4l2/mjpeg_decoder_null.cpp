// SPDX-License-Identifier: Apache-2.0
// The MJPEG decoder when overlayd is built without libjpeg-turbo: asking for it is a clear error.
#include "drivers/v4l2/mjpeg_decoder.h"

namespace overlayd {

Result<std::unique_ptr<MjpegDecoder>> makeMjpegDecoder()
{
    return makeError(ErrorCode::Unsupported, "MJPEG decoding needs libjpeg-turbo (overlayd was built without it)");
}

} // namespace overlayd
