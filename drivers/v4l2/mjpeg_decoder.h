// SPDX-License-Identifier: Apache-2.0
// MjpegDecoder: turns one MJPEG frame from a camera into a YUV frame the blender handles.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "base/result.h"
#include "media/frame.h"
#include "media/pixel_format.h"

namespace overlayd {

class MjpegDecoder
{
public:
    virtual ~MjpegDecoder() = default;
    // Decodes into `out`, which must be YUYV or YUV420 and the JPEG's size. Any chroma subsampling of the JPEG
    // (4:2:0, 4:2:2, 4:4:4, grey ...) is resampled to the output's. Malformed when the data does not decode.
    virtual Status decode(std::span<const uint8_t> jpeg, const FrameView &out) = 0;
};

// libjpeg-turbo's decoder; Unsupported when overlayd was built without it.
Result<std::unique_ptr<MjpegDecoder>> makeMjpegDecoder();

// What an MJPEG stream decodes to for a configured format: YUYV when that was asked for, else YUV420 (I420).
const PixelFormatInfo &mjpegOutputFormat(const PixelFormatInfo *requested);

} // namespace overlayd
