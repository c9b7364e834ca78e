// SPDX-License-Identifier: Apache-2.0
// CAN signal decoding checked without the production trick (reading the 8 bytes as one 64-bit word):
// - a naive walker follows DBC's bit numbering one bit at a time, and canLayoutProblem, canBytesNeeded, canRawBits
//   and canDecode must agree with it for every start bit and length, both byte orders, signed and unsigned, on
//   several byte patterns; a frame one byte too short must give nullopt;
// - hand-worked examples, drawn as DBC references draw them, pin down the conventions the walker itself relies on;
// - layouts that run outside the 8 data bytes, or have no bits, are refused.
// The word-based decoder is easy to get subtly wrong at the edges (Motorola's sawtooth, 64-bit lengths, sign
// extension), so the reference here is deliberately the slow, obvious reading of the DBC rules.
#include "inputs/can_signal.h"

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include <gtest/gtest.h>

using namespace overlayd;

namespace {

using Frame = std::array<uint8_t, 8>;

std::string describe(const CanSignalLayout &l)
{
    return std::string(l.bigEndian ? "Motorola" : "Intel") + (l.isSigned ? " signed" : " unsigned") +
           " start=" + std::to_string(l.startBit) + " length=" + std::to_string(l.length);
}

// The DBC bit numbers a signal occupies, most significant first; a number >= 64 means it left the 8 data bytes.
std::vector<unsigned> walk(const CanSignalLayout &l)
{
    std::vector<unsigned> bits;
    unsigned b = l.startBit;
    for (unsigned i = 0; i < l.length; ++i) {
        bits.push_back(b);
        if (!l.bigEndian)
            b += 1; // Intel: up through the byte, then on into the next byte's bit 0
        else if (b % 8 != 0)
            b -= 1; // Motorola: down through the byte...
        else
            b += 15; // ...and after its bit 0, the next byte's bit 7
    }
    if (!l.bigEndian) // Intel's start bit is the least significant one
        std::reverse(bits.begin(), bits.end());
    return bits;
}

bool bitAt(std::span<const uint8_t> data, unsigned b)
{
    return (data[b / 8] >> (b % 8)) & 1;
}

struct Reference {
    bool fits = true;
    unsigned bytes = 0; // highest byte index touched + 1
    uint64_t raw = 0;
    int64_t value = 0; // raw read as two's complement (signed layouts only)
};

Reference reference(const CanSignalLayout &l, std::span<const uint8_t> data)
{
    Reference r;
    const std::vector<unsigned> bits = walk(l);
    for (unsigned b : bits) {
        r.fits = r.fits && b < 64;
        r.bytes = std::max(r.bytes, b / 8 + 1);
    }
    if (!r.fits)
        return r;
    for (size_t i = 0; i < bits.size(); ++i) {
        const bool bit = bitAt(data, bits[i]);
        r.raw = r.raw << 1 | bit;
        // The most significant bit of a signed value weighs -2^(length-1): start from -1 and keep doubling.
        if (l.isSigned)
            r.value = i == 0 && bit ? -1 : r.value * 2 + bit;
    }
    return r;
}

std::vector<Frame> patterns()
{
    std::vector<Frame> frames{Frame{}, Frame{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF},
                              Frame{0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF}};
    std::mt19937_64 rng(20240607);
    for (int n = 0; n < 5; ++n) {
        Frame f;
        for (uint8_t &byte : f)
            byte = uint8_t(rng());
        frames.push_back(f);
    }
    return frames;
}

CanSignalLayout layout(unsigned start, unsigned length, bool bigEndian, bool isSigned = false, double scale = 1.0,
                       double offset = 0.0)
{
    return CanSignalLayout{start, length, bigEndian, isSigned, scale, offset};
}

std::optional<uint64_t> raw(const CanSignalLayout &l, std::initializer_list<uint8_t> bytes)
{
    return canRawBits(l, std::span<const uint8_t>(bytes.begin(), bytes.size()));
}

std::optional<double> decode(const CanSignalLayout &l, std::initializer_list<uint8_t> bytes)
{
    return canDecode(l, std::span<const uint8_t>(bytes.begin(), bytes.size()));
}

} // namespace

TEST(CanSignal, AgreesWithABitByBitWalkerForEveryLayout)
{
    const std::vector<Frame> frames = patterns();
    int valid = 0;
    for (bool bigEndian : {false, true})
        for (bool isSigned : {false, true})
            for (unsigned start = 0; start < 64; ++start)
                for (unsigned length = 1; length <= 64; ++length) {
                    const CanSignalLayout l = layout(start, length, bigEndian, isSigned, 0.25, -3.0);
                    const Reference shape = reference(l, frames[0]);
                    ASSERT_EQ(canLayoutProblem(l).empty(), shape.fits) << describe(l) << ": " << canLayoutProblem(l);
                    if (!shape.fits)
                        continue;
                    ++valid;
                    ASSERT_EQ(canBytesNeeded(l), shape.bytes) << describe(l);
                    for (const Frame &f : frames) {
                        const std::span<const uint8_t> exact(f.data(), shape.bytes); // no bytes past the signal
                        const Reference want = reference(l, exact);
                        ASSERT_EQ(canRawBits(l, exact), want.raw) << describe(l);
                        ASSERT_EQ(canRawBits(l, std::span<const uint8_t>(f)), want.raw) << describe(l);
                        const std::optional<double> got = canDecode(l, exact);
                        ASSERT_TRUE(got.has_value()) << describe(l);
                        ASSERT_DOUBLE_EQ(*got, (l.isSigned ? double(want.value) : double(want.raw)) * 0.25 - 3.0)
                            << describe(l);
                        const std::span<const uint8_t> shortFrame(f.data(), shape.bytes - 1);
                        ASSERT_EQ(canRawBits(l, shortFrame), std::nullopt) << describe(l);
                        ASSERT_EQ(canDecode(l, shortFrame), std::nullopt) << describe(l);
                    }
                }
    // Per byte order and signedness: Intel keeps sum(64 - start) = 2080 layouts; Motorola keeps, for an MSB in byte
    // k at bit j, 8 * (8 - k) - (7 - j) bits at most, which sums to the same 2080.
    EXPECT_EQ(valid, 4 * 2080);
}

TEST(CanSignal, IntelSixteenBitsAtStartZero)
{
    // byte:     0         1
    // bits:  7......0  15.....8      LSB = bit 0, MSB = bit 15
    // data:    0x34      0x12     -> 0x12 << 8 | 0x34
    EXPECT_EQ(raw(layout(0, 16, false), {0x34, 0x12}), 0x1234u);
}

TEST(CanSignal, MotorolaSixteenBitsAtStartSeven)
{
    // byte:     0         1
    // bits:  7......0  15.....8      MSB = bit 7 (byte 0), then 6..0, then 15..8; LSB = bit 8
    // data:    0x12      0x34     -> 0x12 << 8 | 0x34
    EXPECT_EQ(raw(layout(7, 16, true), {0x12, 0x34}), 0x1234u);
}

TEST(CanSignal, MotorolaTwelveBitsAtStartEleven)
{
    // byte:        1              2
    // bits:   15 14 13 12 11..8  23......16    MSB = bit 11 (byte 1 bit 3): 11,10,9,8 then 23..16; LSB = bit 16
    // data:   0xFA = 1111 1010   0xBC       -> low nibble 0xA, then 0xBC -> 0xABC (the high nibble 0xF is not read)
    const CanSignalLayout l = layout(11, 12, true);
    EXPECT_EQ(canBytesNeeded(l), 3u);
    EXPECT_EQ(raw(l, {0x00, 0xFA, 0xBC}), 0xABCu);
    EXPECT_EQ(raw(l, {0x00, 0xFA}), std::nullopt);
}

TEST(CanSignal, SignedBigEndianSteeringAngle)
{
    // Motorola, MSB bit 7, 16 bits, signed, 0.1 deg per bit: raw 0xFE0C = 65036 = 65036 - 65536 = -500 -> -50.0 deg
    const CanSignalLayout l = layout(7, 16, true, true, 0.1, 0.0);
    EXPECT_EQ(raw(l, {0xFE, 0x0C}), 0xFE0Cu);
    EXPECT_DOUBLE_EQ(*decode(l, {0xFE, 0x0C}), -50.0);
    // and the same bits unsigned: 65036 * 0.1 = 6503.6
    EXPECT_DOUBLE_EQ(*decode(layout(7, 16, true, false, 0.1, 0.0), {0xFE, 0x0C}), 6503.6);
}

TEST(CanSignal, ScaleAndOffset)
{
    // Intel 8 bits at start 0, e.g. a coolant temperature "(0.5,-40)": raw 0xC8 = 200 -> 200 * 0.5 - 40 = 60
    EXPECT_DOUBLE_EQ(*decode(layout(0, 8, false, false, 0.5, -40.0), {0xC8}), 60.0);
}

TEST(CanSignal, IntelNibbleInTheHighHalfOfByteTwo)
{
    // byte 2 = 0xA5 = 1010 0101; bits 23..20 are its high nibble, start bit 20 its LSB -> 0xA
    const CanSignalLayout l = layout(20, 4, false);
    EXPECT_EQ(canBytesNeeded(l), 3u);
    EXPECT_EQ(raw(l, {0xFF, 0xFF, 0xA5}), 0xAu);
}

TEST(CanSignal, SixtyFourBitSignals)
{
    // Intel from bit 0: byte 0 is least significant; Motorola from bit 7: byte 0 is most significant.
    EXPECT_EQ(raw(layout(0, 64, false), {1, 2, 3, 4, 5, 6, 7, 8}), 0x0807060504030201u);
    EXPECT_EQ(raw(layout(7, 64, true), {1, 2, 3, 4, 5, 6, 7, 8}), 0x0102030405060708u);
    // all ones, signed, is -1; unsigned it is 2^64 - 1
    EXPECT_DOUBLE_EQ(*decode(layout(0, 64, false, true), {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}), -1.0);
    EXPECT_DOUBLE_EQ(*decode(layout(7, 64, true, false), {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}),
                     18446744073709551615.0);
    EXPECT_EQ(raw(layout(0, 64, false), {1, 2, 3, 4, 5, 6, 7}), std::nullopt);
}

TEST(CanSignal, OneBitSignals)
{
    // A flag at bit 13 = byte 1 bit 5 (0x20); byte order does not matter for a single bit.
    for (bool bigEndian : {false, true}) {
        EXPECT_EQ(raw(layout(13, 1, bigEndian), {0x00, 0x20}), 1u);
        EXPECT_EQ(raw(layout(13, 1, bigEndian), {0xFF, 0xDF}), 0u);
        // Signed with one bit: the only bit is the sign bit, so raw 1 is -1.
        EXPECT_DOUBLE_EQ(*decode(layout(13, 1, bigEndian, true), {0x00, 0x20}), -1.0);
    }
}

TEST(CanSignal, MotorolaStartBitZeroContinuesIntoTheNextByte)
{
    // MSB at byte 0 bit 0, then byte 1 bit 7: {0x01, 0x80} -> 0b11 = 3, and the signal needs 2 bytes.
    const CanSignalLayout l = layout(0, 2, true);
    EXPECT_EQ(canLayoutProblem(l), "");
    EXPECT_EQ(canBytesNeeded(l), 2u);
    EXPECT_EQ(raw(l, {0x01, 0x80}), 3u);
}

TEST(CanSignal, RefusesLayoutsOutsideTheDataBytes)
{
    const CanSignalLayout refused[] = {
        layout(0, 0, false),  // no bits
        layout(0, 0, true),   // no bits
        layout(0, 65, false), // more than 64 bits
        layout(64, 1, false), // no bit 64
        layout(64, 1, true),  // no bit 64
        layout(60, 8, false), // bits 60..67
        layout(1, 64, false), // bits 1..64
        layout(56, 2, true),  // byte 7 bit 0, then "byte 8"
        layout(59, 5, true),  // 59, 58, 57, 56, then "byte 8"
        layout(6, 64, true),  // 63 bits fit below byte 0 bit 6
    };
    for (const CanSignalLayout &l : refused)
        EXPECT_NE(canLayoutProblem(l), "") << describe(l);
    // and their neighbours that just fit
    EXPECT_EQ(canLayoutProblem(layout(56, 8, false)), "");
    EXPECT_EQ(canLayoutProblem(layout(56, 1, true)), "");
    EXPECT_EQ(canLayoutProblem(layout(59, 4, true)), "");
    EXPECT_EQ(canLayoutProblem(layout(6, 63, true)), "");
}
