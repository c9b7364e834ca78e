// SPDX-License-Identifier: Apache-2.0
// A signal inside a classic CAN frame's 8 data bytes, laid out as a DBC file describes it (SG_ lines), and its
// decoding into a physical value: physical = raw * scale + offset.
//
// Bit numbering (DBC's): bit b is bit (b % 8) of data byte b / 8, bit 0 the byte's least significant bit.
// - little-endian (Intel, "@1"): startBit is the signal's least significant bit; the next bits go up through the
//   byte and on into the next byte's bit 0.
// - big-endian (Motorola, "@0"): startBit is the signal's MOST significant bit; the next bits go down through the
//   byte and on into the next byte's bit 7 (the "sawtooth" DBC editors draw).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace overlayd {

inline constexpr unsigned kCanDataBytes = 8; // classic CAN (CAN FD frames are not read)
inline constexpr uint32_t kMaxStandardCanId = 0x7FF, kMaxExtendedCanId = 0x1FFFFFFF;

struct CanSignalLayout {
    unsigned startBit = 0; // 0..63, in DBC's numbering (see above)
    unsigned length = 8;   // 1..64 bits
    bool bigEndian = false;
    bool isSigned = false; // two's complement over `length` bits
    double scale = 1.0;
    double offset = 0.0;
    bool operator==(const CanSignalLayout &) const = default;
};

// Why a layout cannot be decoded (its bits run outside the 8 data bytes, a zero length, ...), or empty when it can.
std::string canLayoutProblem(const CanSignalLayout &layout);

// The number of data bytes a frame needs to carry the whole signal (a shorter frame is malformed for it).
unsigned canBytesNeeded(const CanSignalLayout &layout);

// The raw bits as an unsigned integer (nullopt when `data` is shorter than canBytesNeeded). The layout must be valid.
std::optional<uint64_t> canRawBits(const CanSignalLayout &layout, std::span<const uint8_t> data);

// The physical value: the raw bits, sign-extended when signed, times scale plus offset.
std::optional<double> canDecode(const CanSignalLayout &layout, std::span<const uint8_t> data);

// What a text slot shows for a value: "12.3 km/h" (`decimals` after the point, then the unit, if any). The config
// loader checks the shortest reading against the slot's limits, so a unit no reading could show is refused.
std::string canReadingText(double value, int decimals, const std::string &unit);

} // namespace overlayd
