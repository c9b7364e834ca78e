// SPDX-License-Identifier: Apache-2.0
// Whole-image colour conversion, row by row. The matrix is folded into 256-entry tables once per call, so the pixel
// loops are additions and table reads; chroma is walked macropixel by macropixel, without divisions.
#include "media/convert/colour_convert.h"

#include <algorithm>
#include <array>
#include <vector>

#include "media/convert/ycbcr_coefficients.h"

namespace overlayd {

namespace {

using Table = std::array<float, 256>;

// Each code value's contribution to Y', Cb and Cr (encoding) or each code's contribution to R', G', B' (decoding).
struct EncodeTables {
    Table yR, yG, yB, cbR, cbG, cbB, crR, crG, crB;
    float yOffset;

    explicit EncodeTables(const YcbcrCoefficients &k) : yOffset(k.yOffset)
    {
        const float kg = 1.0f - k.kr - k.kb;
        const float cbScale = k.cScale / (2.0f * (1.0f - k.kb)), crScale = k.cScale / (2.0f * (1.0f - k.kr));
        for (int v = 0; v < 256; ++v) {
            const float f = float(v);
            yR[v] = k.yScale * k.kr * f, yG[v] = k.yScale * kg * f, yB[v] = k.yScale * k.kb * f;
            cbR[v] = -cbScale * k.kr * f, cbG[v] = -cbScale * kg * f, cbB[v] = cbScale * (1.0f - k.kb) * f;
            crR[v] = crScale * (1.0f - k.kr) * f, crG[v] = -crScale * kg * f, crB[v] = -crScale * k.kb * f;
        }
    }
};

struct DecodeTables {
    Table luma, crToR, cbToG, crToG, cbToB;

    explicit DecodeTables(const YcbcrCoefficients &k)
    {
        const float kg = 1.0f - k.kr - k.kb;
        for (int v = 0; v < 256; ++v) {
            const float l = (float(v) - k.yOffset) / k.yScale, c = (float(v) - 128.0f) / k.cScale;
            luma[v] = l;
            crToR[v] = 2.0f * (1.0f - k.kr) * c;
            cbToB[v] = 2.0f * (1.0f - k.kb) * c;
            // G' = (Y' - kr R' - kb B') / kg with R' = Y' + crToR, B' = Y' + cbToB.
            crToG[v] = -k.kr * crToR[v] / kg;
            cbToG[v] = -k.kb * cbToB[v] / kg;
        }
    }
};

// Running sums of one chroma row, averaged when its macropixel rows are complete.
struct ChromaSums {
    std::vector<float> cb, cr;
    std::vector<unsigned> count;

    explicit ChromaSums(unsigned samples) : cb(samples), cr(samples), count(samples) {}
    void flush(uint8_t *cbOut, uint8_t *crOut)
    {
        for (size_t c = 0; c < count.size(); ++c) {
            const float inverse = 1.0f / float(count[c]);
            cbOut[c] = toCode(cb[c] * inverse);
            crOut[c] = toCode(cr[c] * inverse);
            cb[c] = cr[c] = 0.0f, count[c] = 0;
        }
    }
};

void encodeRow(const EncodeTables &t, const uint8_t *px, unsigned width, unsigned hSub, uint8_t *luma, ChromaSums *sums)
{
    for (unsigned x = 0; x < width; ++x, px += 3)
        luma[x] = toCode(t.yOffset + t.yR[px[0]] + t.yG[px[1]] + t.yB[px[2]]);
    if (!sums)
        return;
    px -= size_t(width) * 3;
    for (unsigned c = 0, x = 0; x < width; ++c) {
        for (const unsigned end = std::min(x + hSub, width); x < end; ++x, px += 3) {
            sums->cb[c] += 128.0f + t.cbR[px[0]] + t.cbG[px[1]] + t.cbB[px[2]];
            sums->cr[c] += 128.0f + t.crR[px[0]] + t.crG[px[1]] + t.crB[px[2]];
            ++sums->count[c];
        }
    }
}

} // namespace

YcbcrImage rgbToYcbcr(const RgbImage &image, Colorimetry colorimetry, unsigned hSub, unsigned vSub, bool hasChroma)
{
    YcbcrImage out;
    rgbToYcbcr(image, colorimetry, hSub, vSub, hasChroma, out);
    return out;
}

void rgbToYcbcr(const RgbImage &image, Colorimetry colorimetry, unsigned hSub, unsigned vSub, bool hasChroma,
                YcbcrImage &out)
{
    const EncodeTables tables(YcbcrCoefficients::of(colorimetry));
    out.reshape(image.width, image.height, hSub, vSub, hasChroma);
    const unsigned cw = out.chromaWidth();
    ChromaSums sums(hasChroma ? cw : 0);
    for (unsigned y = 0; y < image.height; ++y) {
        encodeRow(tables, image.row(y), image.width, hSub, &out.y[size_t(y) * image.width],
                  hasChroma ? &sums : nullptr);
        if (hasChroma && ((y + 1) % vSub == 0 || y + 1 == image.height))
            sums.flush(&out.cb[size_t(y / vSub) * cw], &out.cr[size_t(y / vSub) * cw]);
    }
}

RgbImage ycbcrToRgb(const YcbcrImage &image, Colorimetry colorimetry)
{
    const DecodeTables t(YcbcrCoefficients::of(colorimetry));
    RgbImage out = RgbImage::allocate(image.width, image.height);
    const unsigned cw = image.chromaWidth();
    for (unsigned y = 0; y < image.height; ++y) {
        const uint8_t *luma = &image.y[size_t(y) * image.width];
        uint8_t *px = out.row(y);
        if (!image.hasChroma) {
            for (unsigned x = 0; x < image.width; ++x, px += 3)
                px[0] = px[1] = px[2] = toCode(t.luma[luma[x]]);
            continue;
        }
        const uint8_t *cbRow = &image.cb[size_t(y / image.vSub) * cw], *crRow = &image.cr[size_t(y / image.vSub) * cw];
        for (unsigned c = 0, x = 0; x < image.width; ++c) {
            const float r = t.crToR[crRow[c]], g = t.cbToG[cbRow[c]] + t.crToG[crRow[c]], b = t.cbToB[cbRow[c]];
            for (const unsigned end = std::min(x + image.hSub, image.width); x < end; ++x, px += 3) {
                const float l = t.luma[luma[x]];
                px[0] = toCode(l + r), px[1] = toCode(l + g), px[2] = toCode(l + b);
            }
        }
    }
    return out;
}

YcbcrImage resampleChroma(const YcbcrImage &image, unsigned hSub, unsigned vSub)
{
    YcbcrImage out = YcbcrImage::allocate(image.width, image.height, hSub, vSub, image.hasChroma);
    out.y = image.y;
    if (!image.hasChroma)
        return out;
    const unsigned cw = out.chromaWidth(), oldCw = image.chromaWidth();
    ChromaSums sums(cw);
    for (unsigned y = 0; y < image.height; ++y) {
        const size_t oldRow = size_t(y / image.vSub) * oldCw;
        for (unsigned x = 0; x < image.width; ++x) {
            sums.cb[x / hSub] += image.cb[oldRow + x / image.hSub];
            sums.cr[x / hSub] += image.cr[oldRow + x / image.hSub];
            ++sums.count[x / hSub];
        }
        if ((y + 1) % vSub == 0 || y + 1 == image.height)
            sums.flush(&out.cb[size_t(y / vSub) * cw], &out.cr[size_t(y / vSub) * cw]);
    }
    return out;
}

} // namespace overlayd
