// SPDX-License-Identifier: Apache-2.0
// The tables of JfifMapping, from the BT.601/BT.709 equations in media/convert/ycbcr_coefficients.h.
#include "media/jpeg/jfif_mapping.h"

#include <cmath>

#include "media/convert/ycbcr_coefficients.h"

namespace overlayd {

namespace {

// Y' on the 0..255 scale and Pb, Pr = (B' - Y') / (2 (1 - kb)), (R' - Y') / (2 (1 - kr)) on the same scale: the
// code values with the range taken out, so that only the matrices differ between colorimetries.
struct Ypbpr {
    double y = 0.0, pb = 0.0, pr = 0.0;
};

// Source matrix -> R'G'B' -> BT.601 matrix, for one vector; the map is linear, so its columns are the images of
// unit Pb and unit Pr (unit Y' maps to itself).
Ypbpr toBt601(const YcbcrCoefficients &from, const YcbcrCoefficients &to, Ypbpr v)
{
    const double r = v.y + 2.0 * (1.0 - from.kr) * v.pr;
    const double b = v.y + 2.0 * (1.0 - from.kb) * v.pb;
    const double g = (v.y - from.kr * r - from.kb * b) / (1.0 - from.kr - from.kb);
    const double y = to.kr * r + (1.0 - to.kr - to.kb) * g + to.kb * b;
    return {y, (b - y) / (2.0 * (1.0 - to.kb)), (r - y) / (2.0 * (1.0 - to.kr))};
}

int32_t fixed(double value)
{
    return int32_t(std::lround(value * 65536.0));
}

constexpr int32_t kHalf = 1 << 15;

} // namespace

JfifMapping::JfifMapping(Colorimetry colorimetry) : colorimetry_(colorimetry)
{
    const YcbcrCoefficients from = YcbcrCoefficients::of(colorimetry);
    const YcbcrCoefficients to = YcbcrCoefficients::of({YcbcrMatrix::Bt601, ColourRange::Full});
    const Ypbpr fromPb = toBt601(from, to, {0.0, 1.0, 0.0}), fromPr = toBt601(from, to, {0.0, 0.0, 1.0});
    for (int v = 0; v < 256; ++v) {
        const double y = (v - from.yOffset) / from.yScale, c = (v - 128.0) / from.cScale;
        lumaBytes_[v] = toCode(float(y));
        chromaBytes_[v] = toCode(float(128.0 + c));
        yFixed_[v] = fixed(y) + kHalf;
        cbToY_[v] = fixed(fromPb.y * c);
        crToY_[v] = fixed(fromPr.y * c);
        cbToCb_[v] = fixed(128.0 + fromPb.pb * c) + kHalf;
        crToCb_[v] = fixed(fromPr.pb * c);
        cbToCr_[v] = fixed(fromPb.pr * c);
        crToCr_[v] = fixed(128.0 + fromPr.pr * c) + kHalf;
    }
}

} // namespace overlayd
