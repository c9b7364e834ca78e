// JpegEncoder: compresses frames to baseline JFIF with libjpeg-turbo, straight from the frame's own planes, for the
// HTTP MJPEG stream and snapshots.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "base/result.h"
#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/jpeg/jfif_mapping.h"
#include "media/jpeg/jfif_planes.h"

namespace overlayd {

// Keeps its libjpeg-turbo handle, its scratch planes and its output buffer from one call to the next: once a frame
// size has been seen, encoding another frame of that size allocates nothing on our side (libjpeg's own per-image
// pools aside). Move-only; one encoder per thread.
class JpegEncoder
{
public:
    // Io when libjpeg-turbo cannot make a compressor.
    static Result<JpegEncoder> create();

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

    explicit JpegEncoder(void *handle) : handle_(handle) {}

    Status compressYcbcr(const FrameView &frame, Colorimetry colorimetry, int quality, unsigned long &size);
    Status compressRgb(const FrameView &frame, int quality, unsigned long &size);
    Status failed(const FrameView &frame) const;
    unsigned char *reserve(const FrameView &frame, int subsampling);

    std::unique_ptr<void, HandleDeleter> handle_; // a tjhandle
    JfifMapping mapping_{Colorimetry{}};          // rebuilt only when the colorimetry changes
    JfifPlanes planes_;
    std::vector<uint8_t> jpeg_; // tjBufSize() bytes: libjpeg-turbo writes into it without reallocating
};

} // namespace overlayd
