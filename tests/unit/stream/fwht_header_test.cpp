// SPDX-License-Identifier: Apache-2.0
// fwhtIsKeyframe against headers laid out by hand from the kernel's struct fwht_cframe_hdr (codec-fwht.h) and
// V4L2_FWHT_FL_I_FRAME (linux/v4l2-controls.h), not from the code's own constants.
#include <gtest/gtest.h>

#include <linux/v4l2-controls.h>

#include <vector>

#include "stream/fwht_header.h"

using overlayd::fwhtIsKeyframe;

namespace {

// magic1, magic2, version 3, 640x480, flags, then colorspace .. size: eleven 32-bit words.
std::vector<uint8_t> header(uint32_t flags)
{
    std::vector<uint8_t> bytes = {0x4f, 0x4f, 0x4f, 0x4f, 0xff, 0xff, 0xff, 0xff, 0, 0,
                                  0,    3,    0,    0,    2,    0x80, 0,    0,    1, 0xe0};
    for (int shift = 24; shift >= 0; shift -= 8)
        bytes.push_back(uint8_t(flags >> shift));
    bytes.resize(44 + 16, 0x11); // the other header words, then some frame data
    return bytes;
}

} // namespace

TEST(FwhtHeader, TheIFrameFlagDecides)
{
    // What vicodec writes for 4:2:0 YUV: 3 components (offset 16), YUV encoding (bit 19), plus the I-frame bit.
    const uint32_t yuv420 = (2u << 16) | (1u << 19);
    EXPECT_TRUE(fwhtIsKeyframe(header(yuv420 | V4L2_FWHT_FL_I_FRAME).data(), 60));
    EXPECT_FALSE(fwhtIsKeyframe(header(yuv420).data(), 60));
}

TEST(FwhtHeader, NotAHeaderIsNoKeyframe)
{
    auto bytes = header(V4L2_FWHT_FL_I_FRAME);
    EXPECT_FALSE(fwhtIsKeyframe(bytes.data(), 43)); // shorter than the header
    EXPECT_FALSE(fwhtIsKeyframe(nullptr, 60));
    bytes[4] = 0;
    EXPECT_FALSE(fwhtIsKeyframe(bytes.data(), 60)); // wrong magic
}
