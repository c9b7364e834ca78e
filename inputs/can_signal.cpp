// SPDX-License-Identifier: Apache-2.0
// Decoding works on the 8 data bytes as one 64-bit word: read little-endian for Intel signals (a DBC bit number is
// then the word's bit number), big-endian for Motorola ones (where DBC's sawtooth becomes one contiguous run of
// bits, from the start bit's position in that word downwards).
#include "inputs/can_signal.h"

#include "base/number_text.h"

namespace overlayd {

namespace {

// Where the signal's least significant bit lies in the word the layout's byte order reads.
int lowestBit(const CanSignalLayout &layout)
{
    if (!layout.bigEndian)
        return int(layout.startBit);
    const int msb = int(7 - layout.startBit / 8) * 8 + int(layout.startBit % 8);
    return msb - int(layout.length) + 1;
}

uint64_t wordOf(std::span<const uint8_t> data, bool bigEndian)
{
    uint64_t word = 0;
    for (size_t i = 0; i < kCanDataBytes; ++i) {
        const uint64_t byte = i < data.size() ? data[i] : 0;
        word |= byte << (bigEndian ? 8 * (7 - i) : 8 * i);
    }
    return word;
}

} // namespace

std::string canLayoutProblem(const CanSignalLayout &layout)
{
    if (layout.length < 1 || layout.length > 64)
        return "length must be 1..64 bits";
    if (layout.startBit > 63)
        return "start_bit must be 0..63";
    if (!layout.bigEndian && layout.startBit + layout.length > 64)
        return "a little-endian signal from bit " + std::to_string(layout.startBit) + " with " +
               std::to_string(layout.length) + " bits runs past the 8th data byte";
    if (layout.bigEndian && lowestBit(layout) < 0)
        return "a big-endian signal whose most significant bit is bit " + std::to_string(layout.startBit) +
               " has at most " + std::to_string(int(layout.length) + lowestBit(layout)) +
               " bits before the 8th data byte ends";
    return {};
}

unsigned canBytesNeeded(const CanSignalLayout &layout)
{
    if (!layout.bigEndian)
        return (layout.startBit + layout.length - 1) / 8 + 1;
    return 7 - unsigned(lowestBit(layout)) / 8 + 1;
}

std::optional<uint64_t> canRawBits(const CanSignalLayout &layout, std::span<const uint8_t> data)
{
    if (data.size() < canBytesNeeded(layout))
        return std::nullopt;
    const uint64_t word = wordOf(data, layout.bigEndian);
    const uint64_t mask = layout.length == 64 ? ~uint64_t(0) : (uint64_t(1) << layout.length) - 1;
    return (word >> lowestBit(layout)) & mask;
}

std::optional<double> canDecode(const CanSignalLayout &layout, std::span<const uint8_t> data)
{
    const std::optional<uint64_t> raw = canRawBits(layout, data);
    if (!raw)
        return std::nullopt;
    double value = double(*raw);
    if (layout.isSigned && layout.length < 64 && (*raw >> (layout.length - 1)) & 1)
        value = double(int64_t(*raw | ~((uint64_t(1) << layout.length) - 1)));
    else if (layout.isSigned && layout.length == 64)
        value = double(int64_t(*raw));
    return value * layout.scale + layout.offset;
}

std::string canReadingText(double value, int decimals, const std::string &unit)
{
    const std::string text = formatted("%.*f", decimals, value);
    return unit.empty() ? text : text + " " + unit;
}

} // namespace overlayd
