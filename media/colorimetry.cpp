// SPDX-License-Identifier: Apache-2.0
// Colorimetry from the V4L2 format fields.
#include "media/colorimetry.h"

#include <linux/videodev2.h>

namespace overlayd {

Colorimetry colorimetryFromV4l2(uint32_t colorspace, uint32_t ycbcrEnc, uint32_t quantization)
{
    if (ycbcrEnc == V4L2_YCBCR_ENC_DEFAULT)
        ycbcrEnc = V4L2_MAP_YCBCR_ENC_DEFAULT(colorspace);
    if (quantization == V4L2_QUANTIZATION_DEFAULT)
        quantization = V4L2_MAP_QUANTIZATION_DEFAULT(false, colorspace, ycbcrEnc);

    Colorimetry result;
    const bool is601 = ycbcrEnc == V4L2_YCBCR_ENC_601 || ycbcrEnc == V4L2_YCBCR_ENC_XV601;
    result.matrix = is601 ? YcbcrMatrix::Bt601 : YcbcrMatrix::Bt709;
    result.range = quantization == V4L2_QUANTIZATION_FULL_RANGE ? ColourRange::Full : ColourRange::Limited;
    return result;
}

const char *matrixName(YcbcrMatrix matrix)
{
    return matrix == YcbcrMatrix::Bt601 ? "BT.601" : "BT.709";
}

const char *rangeName(ColourRange range)
{
    return range == ColourRange::Limited ? "limited" : "full";
}

} // namespace overlayd
