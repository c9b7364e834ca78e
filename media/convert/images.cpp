// Allocation of the converters' images.
#include "media/convert/images.h"

namespace overlayd {

RgbImage RgbImage::allocate(unsigned width, unsigned height)
{
    return {width, height, std::vector<uint8_t>(size_t(width) * height * 3)};
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
