// SPDX-License-Identifier: Apache-2.0
// The decoded format of an MJPEG stream.
#include "drivers/v4l2/mjpeg_decoder.h"

#include <linux/videodev2.h>

namespace overlayd {

const PixelFormatInfo &mjpegOutputFormat(const PixelFormatInfo *requested)
{
    // YUYV keeps 4:2:2 cameras' chroma; everything else gets the smaller I420.
    if (requested && requested->fourcc == V4L2_PIX_FMT_YUYV)
        return *requested;
    return *pixelFormatFromFourcc(V4L2_PIX_FMT_YUV420);
}

} // namespace overlayd
