// SPDX-License-Identifier: Apache-2.0
// JfifPlanes: a Y'CbCr frame's samples as the separate Y, Cb and Cr planes that libjpeg-turbo compresses from, in
// JFIF's full-range BT.601 and with the frame's own chroma subsampling.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "base/result.h"
#include "media/frame.h"
#include "media/jpeg/jfif_mapping.h"

namespace overlayd {

class JfifPlanes
{
public:
    // Points at the planes of `frame` (a checked Y'CbCr frame) wherever they already hold contiguous samples that
    // need no conversion (I420's three planes, NV12's luma, in full-range BT.601), and converts the rest into
    // scratch planes: packed 4:2:2 is de-interleaved, semi-planar chroma split, the range expanded and the matrix
    // changed as `mapping` says; luma is given the padding to whole chroma sites libjpeg-turbo reads (an odd-sized
    // frame's luma is always copied). The scratch planes keep their memory while the frame size stays the same.
    // Unsupported for a table entry whose samples are not at fixed steps (none today).
    Status gather(const FrameView &frame, const JfifMapping &mapping);

    // 1 for luma-only frames (GREY), else 3.
    unsigned count() const { return count_; }
    const std::array<const uint8_t *, 3> &data() const { return data_; }
    const std::array<int, 3> &strides() const { return strides_; }

    // A scratch plane's memory (nullptr before its first use), for the test that steady frames allocate nothing.
    const uint8_t *scratch(unsigned plane) const { return scratch_[plane].data(); }

private:
    std::array<const uint8_t *, 3> data_{};
    std::array<int, 3> strides_{};
    unsigned count_ = 0;
    std::array<std::vector<uint8_t>, 3> scratch_;
    std::vector<int32_t> lumaOffsets_; // one chroma row's luma offsets, when the matrix changes
};

} // namespace overlayd
