// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: any CAN frame (from the bus, untrusted) decoded through any layout the config accepts. The first
// 4 bytes choose the layout (start bit, length, byte order and sign); the rest are the frame's data bytes, of any
// length (a short frame must come back as nullopt, never as a read past its end).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "inputs/can_signal.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 4)
        return 0;
    overlayd::CanSignalLayout layout;
    layout.startBit = data[0] % 64;
    layout.length = 1 + data[1] % 64;
    layout.bigEndian = data[2] & 1;
    layout.isSigned = data[2] & 2;
    layout.scale = 0.1 * (1 + data[3]);
    if (!overlayd::canLayoutProblem(layout).empty())
        return 0;
    const std::span<const uint8_t> frame(data + 4, std::min<size_t>(size - 4, overlayd::kCanDataBytes));
    const auto value = overlayd::canDecode(layout, frame);
    if (value.has_value() != (frame.size() >= overlayd::canBytesNeeded(layout)))
        __builtin_trap(); // a frame long enough must decode, a short one must not
    return 0;
}
