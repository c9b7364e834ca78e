// SPDX-License-Identifier: Apache-2.0
// Allocation of the converters' images.
#include "media/convert/images.h"

namespace overlayd {

RgbImage RgbImage::allocate(unsigned width, unsigned height)
{
    return {width, height, std::vector<uint8_t>(size_t(width) * height * 3)};
}

void RgbImage::reshape(unsigned w, unsigned h)
{
    width = w;
    height = h;
    rgb.resize(size_t(w) * h * 3);
}

void YcbcrImage::reshape(unsigned w, unsigned h, unsigned hs, unsigned vs, bool chroma)
{
    width = w;
    height = h;
    hSub = hs;
    vSub = vs;
    hasChroma = chroma;
    y.resize(size_t(w) * h);
    cb.resize(chroma ? size_t(chromaWidth()) * chromaHeight() : 0);
    cr.resize(cb.size());
}

YcbcrImage YcbcrImage::allocate(unsigned width, unsigned height, unsigned hSub, unsigned vSub, bool hasChroma)
{
    YcbcrImage image{width, height, hSub, vSub, hasChroma, {}, {}, {}};
    image.y.resize(size_t(width) * height);
    if (hasChroma) {
        image.cb.resize(size_t(image.chromaWidth()) * image.chromaHeight());
        image.cr.resize(image.cb.size());
    }
    return image;
}

} // namespace overlayd
