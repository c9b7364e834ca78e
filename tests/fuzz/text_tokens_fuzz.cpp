// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any bytes as a screen text (a config's `text = "..."`, checked by checkTokens at load) and as a
// slot's text (what HTTP, a text file or a CAN input sets at run time), expanded for a frame as the renderer does.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "overlay/shapes/text_tokens.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    // The first 8 bytes, when there are that many, pick the frame's sequence number and wall clock.
    uint64_t seed = 0;
    if (size >= sizeof seed) {
        std::memcpy(&seed, data, sizeof seed);
        data += sizeof seed;
        size -= sizeof seed;
    }
    const std::string_view text(reinterpret_cast<const char *>(data), size);
    overlayd::FrameMetadata metadata;
    metadata.sequence = seed;
    // Up to 2^33 s after 1970 (year 2242): the clock counts nanoseconds in 64 bits, so later would overflow.
    metadata.wallClock = std::chrono::system_clock::time_point(std::chrono::seconds(int64_t(seed % (1ull << 33))));
    overlayd::SlotTexts slots;
    if (overlayd::checkSlotText(text))
        slots["s"] = std::string(text);
    if (!overlayd::checkTokens(text))
        return 0;
    std::vector<std::string> names;
    overlayd::appendSlotNames(text, names);
    std::string out;
    overlayd::expandTokens(text, metadata, double(seed % 100000) / 7.0, out, &slots);
    overlayd::expandTokens("{slot:s} {frame} {fps}", metadata, 30.0, out, &slots);
    return 0;
}
