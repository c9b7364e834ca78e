// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as an image file (an image annotation's PNG/JPEG, a replay frame): the header read,
// then both decodings, under a small side limit so that a header claiming a huge image is refused, not allocated.
#include <cstddef>
#include <cstdint>
#include <span>

#include "media/codec/image_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const std::span<const uint8_t> file(data, size);
    (void)overlayd::readImageInfo(file);
    (void)overlayd::decodeImage(file, overlayd::ImageChannels::Rgb, 1024);
    (void)overlayd::decodeImage(file, overlayd::ImageChannels::Rgba, 1024);
    return 0;
}
