// SPDX-License-Identifier: Apache-2.0
// JpegEncoder: compresses frames to baseline JFIF with libjpeg-turbo, straight from the frame's own planes, for the
// HTTP MJPEG stream and snapshots.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "base/result.h"
#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/jpeg/jfif_mapping.h"
#include "media/jpeg/jfif_planes.h"

namespace overlayd {

// What a 4:2:2 frame's chroma becomes. A stream's parts are sent many times a second to every viewer: 4:2:0 is
// what MJPEG servers (µStreamer, cameras) send and browsers expect, about a sixth smaller than 4:2:2 at the same
// quality setting, with half the vertical colour resolution (SSIM against the uncompressed frame drops by about
// 0.002 on an overlaid frame). A file a person keeps (the snapshot sink) keeps the frame's own.
enum class JpegChroma {
    AsFrame, // the frame's own subsampling
    Halved,  // 4:2:2 sent as 4:2:0 (chroma rows averaged in pairs) when the frame's height is even
};

// Keeps its libjpeg-turbo handle, its scratch planes and its output buffer from one call to the next: once a frame
// size has been seen, encoding another frame of that size allocates nothing on our side (libjpeg's own per-image
// pools aside). Move-only; one encoder per thread.
class JpegEncoder
{
public:
    // Io when libjpeg-turbo cannot make a compressor.
    static Result<JpegEncoder> create(JpegChroma chroma = JpegChroma::AsFrame);

    // Compresses `frame` into `out` (replaced; its capacity is reused), at quality 1..100. Y'CbCr samples are read
    // in `colorimetry` and written as JFIF's full-range BT.601; formats keep their chroma subsampling (YUYV and
    // NV16 give 4:2:2, NV12 and I420 4:2:0), RGB formats give 4:2:0 and ignore `colorimetry`, GREY gives a
    // greyscale JPEG. InvalidArgument for a bad quality or a frame that checkFrame refuses, Unsupported for a
    // format libjpeg-turbo cannot take, Io when compression fails.
    Status encode(const FrameView &frame, Colorimetry colorimetry, int quality, std::vector<uint8_t> &out);

    // The planes the last Y'CbCr frame was compressed from (tests check that they stay put between frames).
    const JfifPlanes &planes() const { return planes_; }

private:
    struct HandleDeleter {
        void operator()(void *handle) const;
    };

    JpegEncoder(void *handle, JpegChroma chroma) : handle_(handle), chroma_(chroma) {}

    // Averages the gathered 4:2:2 chroma planes' rows in pairs into halved_, and points `planes` at them.
    void halveChroma(const FrameView &frame, const unsigned char *planes[3], std::array<int, 3> &strides);

    Status compressYcbcr(const FrameView &frame, Colorimetry colorimetry, int quality, unsigned long &size);
    Status compressRgb(const FrameView &frame, int quality, unsigned long &size);
    Status failed(const FrameView &frame) const;
    unsigned char *reserve(const FrameView &frame, int subsampling);

    std::unique_ptr<void, HandleDeleter> handle_; // a tjhandle
    JpegChroma chroma_;
    std::array<std::vector<uint8_t>, 2> halved_; // Cb, Cr at 4:2:0 (JpegChroma::Halved)
    JfifMapping mapping_{Colorimetry{}};         // rebuilt only when the colorimetry changes
    JfifPlanes planes_;
    std::vector<uint8_t> jpeg_; // tjBufSize() bytes: libjpeg-turbo writes into it without reallocating
};

} // namespace overlayd
