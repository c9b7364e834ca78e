// SPDX-License-Identifier: Apache-2.0
// fwhtIsKeyframe: whether a frame of vicodec's FWHT stream is an I-frame, read from its header. vicodec's encoder
// flags none of its output buffers V4L2_BUF_FLAG_KEYFRAME (only its decoder flags what it decodes), so GStreamer
// marks every encoded frame a delta unit; the header's flags are what says.
#pragma once

#include <cstddef>
#include <cstdint>

namespace overlayd {

// The kernel's struct fwht_cframe_hdr (drivers/media/test-drivers/vicodec/codec-fwht.h): two magic words, then
// big-endian version, width, height, flags, ...; V4L2_FWHT_FL_I_FRAME is bit 10 of flags (linux/v4l2-controls.h).
inline constexpr size_t kFwhtHeaderBytes = 44;
inline constexpr size_t kFwhtFlagsOffset = 20;
inline constexpr uint32_t kFwhtIFrameFlag = 1u << 10;

// False for anything that is not a whole FWHT header (too short, wrong magic).
bool fwhtIsKeyframe(const uint8_t *data, size_t size);

} // namespace overlayd
