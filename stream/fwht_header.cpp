// SPDX-License-Identifier: Apache-2.0
// fwhtIsKeyframe: the magic is 0x4f4f4f4f then 0xffffffff (vicodec's FWHT_MAGIC1, FWHT_MAGIC2), byte for byte.
#include "stream/fwht_header.h"

#include <cstring>

namespace overlayd {

bool fwhtIsKeyframe(const uint8_t *data, size_t size)
{
    static constexpr uint8_t kMagic[8] = {0x4f, 0x4f, 0x4f, 0x4f, 0xff, 0xff, 0xff, 0xff};
    if (data == nullptr || size < kFwhtHeaderBytes || std::memcmp(data, kMagic, sizeof(kMagic)) != 0)
        return false;
    const uint8_t *flags = data + kFwhtFlagsOffset;
    const uint32_t value = uint32_t(flags[0]) << 24 | uint32_t(flags[1]) << 16 | uint32_t(flags[2]) << 8 | flags[3];
    return (value & kFwhtIFrameFlag) != 0;
}

} // namespace overlayd
