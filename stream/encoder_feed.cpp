// SPDX-License-Identifier: Apache-2.0
// EncoderFeed: slots are allocated once per format; a slot goes back to the free list from whichever thread drops
// the last reference to its EncoderInput.
#include "stream/encoder_feed.h"

#include <cstring>
#include <mutex>
#include <vector>

#include "media/convert/colour_convert.h"
#include "media/convert/frame_convert.h"

namespace overlayd {

struct EncoderFeed::Pool {
    std::mutex mutex;
    std::vector<std::vector<uint8_t>> slots;
    std::vector<size_t> free;
    FeedCounters counters;
};

EncoderFeed::EncoderFeed(unsigned slots) : pool_(std::make_shared<Pool>())
{
    pool_->slots.resize(slots);
}

EncoderFeed::~EncoderFeed() = default;

Result<EngineFormat> EncoderFeed::open(const StreamFormat &format)
{
    if (format.format == nullptr || format.width == 0 || format.height == 0)
        return makeError(ErrorCode::InvalidArgument, "the encoder needs a stream format");
    if (format.width % 2 != 0 || format.height % 2 != 0)
        return makeError(ErrorCode::Unsupported, "the encoder takes frames of even width and height, not " +
                                                     std::to_string(format.width) + "x" +
                                                     std::to_string(format.height));
    format_ = format;
    colorimetry_ = format.colorimetry;
    const size_t bytes = size_t(format.width) * format.height * 3 / 2;
    std::lock_guard lock(pool_->mutex);
    // A slot's bytes are re-allocated here: the engine must have let go of every frame (closed) first.
    if (pool_->counters.inFlight != 0)
        return makeError(ErrorCode::InvalidArgument,
                         "the encoder still holds " + std::to_string(pool_->counters.inFlight) + " frames");
    pool_->free.clear();
    for (size_t i = 0; i < pool_->slots.size(); ++i) {
        pool_->slots[i].assign(bytes, 0);
        pool_->free.push_back(i);
    }
    return EngineFormat{format.width, format.height, format.fps, false, colorimetry_};
}

bool EncoderFeed::copyInto(uint8_t *slot, const FrameView &frame)
{
    const unsigned w = frame.width, h = frame.height;
    const PixelFormatInfo &info = *frame.format;
    auto copyPlane = [](uint8_t *to, const uint8_t *from, unsigned stride, unsigned width, unsigned rows) {
        for (unsigned y = 0; y < rows; ++y)
            std::memcpy(to + size_t(y) * width, from + size_t(y) * stride, width);
    };
    uint8_t *y = slot, *u = slot + size_t(w) * h, *v = u + size_t(w / 2) * (h / 2);
    if (info.name == "YUV420") { // already I420: one copy per plane, no conversion
        copyPlane(y, frame.planes[0].data, frame.planes[0].stride, w, h);
        copyPlane(u, frame.planes[1].data, frame.planes[1].stride, w / 2, h / 2);
        copyPlane(v, frame.planes[2].data, frame.planes[2].stride, w / 2, h / 2);
        return true;
    }
    if (info.name == "NV12") { // the camera's usual format: Y copied, CbCr de-interleaved in the same pass
        copyPlane(y, frame.planes[0].data, frame.planes[0].stride, w, h);
        for (unsigned row = 0; row < h / 2; ++row) {
            const uint8_t *from = frame.planes[1].data + size_t(row) * frame.planes[1].stride;
            uint8_t *toU = u + size_t(row) * (w / 2), *toV = v + size_t(row) * (w / 2);
            for (unsigned x = 0; x < w / 2; ++x)
                toU[x] = from[2 * x], toV[x] = from[2 * x + 1];
        }
        return true;
    }
    if (info.name == "YUYV") { // 4:2:2 to 4:2:0: each chroma sample the mean of its two rows
        for (unsigned row = 0; row < h; row += 2) {
            const uint8_t *top = frame.planes[0].data + size_t(row) * frame.planes[0].stride;
            const uint8_t *bottom = top + frame.planes[0].stride;
            uint8_t *toY = y + size_t(row) * w, *toU = u + size_t(row / 2) * (w / 2),
                    *toV = v + size_t(row / 2) * (w / 2);
            for (unsigned x = 0; x < w; ++x)
                toY[x] = top[2 * x], toY[w + x] = bottom[2 * x];
            for (unsigned x = 0; x < w / 2; ++x) {
                toU[x] = uint8_t((top[4 * x + 1] + bottom[4 * x + 1] + 1) / 2);
                toV[x] = uint8_t((top[4 * x + 3] + bottom[4 * x + 3] + 1) / 2);
            }
        }
        return true;
    }
    // Any other format through the general converter (RGB is encoded with the stream's colorimetry).
    if (!frameToYcbcr(frame, colorimetry_, scratch_, rgbScratch_))
        return false;
    if (!scratch_.hasChroma) { // GREY: neutral chroma
        std::memcpy(y, scratch_.y.data(), size_t(w) * h);
        std::memset(u, 128, size_t(w / 2) * (h / 2) * 2);
        return true;
    }
    const YcbcrImage &image =
        scratch_.hSub == 2 && scratch_.vSub == 2 ? scratch_ : (scratch_ = resampleChroma(scratch_, 2, 2));
    std::memcpy(y, image.y.data(), size_t(w) * h);
    std::memcpy(u, image.cb.data(), size_t(w / 2) * (h / 2));
    std::memcpy(v, image.cr.data(), size_t(w / 2) * (h / 2));
    return true;
}

std::optional<EncoderInput> EncoderFeed::fill(const FrameView &frame, const FrameMetadata &metadata,
                                              std::chrono::nanoseconds blendedTime)
{
    if (frame.width != format_.width || frame.height != format_.height || frame.format == nullptr)
        return std::nullopt;
    size_t index;
    {
        std::lock_guard lock(pool_->mutex);
        if (pool_->free.empty()) {
            ++pool_->counters.dropped;
            return std::nullopt;
        }
        index = pool_->free.back();
        pool_->free.pop_back();
        ++pool_->counters.inFlight;
    }
    std::vector<uint8_t> &bytes = pool_->slots[index];
    // The slot's release: back on the free list, from whichever thread lets the frame go last.
    std::shared_ptr<void> owner(bytes.data(), [pool = pool_, index](void *) {
        std::lock_guard lock(pool->mutex);
        pool->free.push_back(index);
        --pool->counters.inFlight;
    });
    const bool converted = frame.format->name != "YUV420";
    if (!copyInto(bytes.data(), frame))
        return std::nullopt; // `owner` gives the slot back
    {
        std::lock_guard lock(pool_->mutex);
        ++pool_->counters.copied;
        pool_->counters.converted += converted ? 1 : 0;
    }
    return EncoderInput{
        std::move(owner), bytes.data(), bytes.size(), metadata.sequence, metadata.timestamp, blendedTime, {}};
}

void EncoderFeed::setLeaseLimit(unsigned limit)
{
    leaseLimit_ = limit;
}

std::optional<EncoderInput> EncoderFeed::lease(std::shared_ptr<const FrameLease> lease,
                                               std::chrono::nanoseconds blendedTime)
{
    {
        std::lock_guard lock(pool_->mutex);
        if (pool_->counters.inFlight >= leaseLimit_) {
            ++pool_->counters.dropped;
            return std::nullopt;
        }
        ++pool_->counters.inFlight;
        ++pool_->counters.zeroCopy;
    }
    const FrameView &frame = lease->view();
    EncoderInput input;
    input.sequence = lease->metadata().sequence;
    input.captureTime = lease->metadata().timestamp;
    input.blendedTime = blendedTime;
    input.dmabuf.fd = frame.planes[0].dmabufFd;
    for (unsigned p = 0; p < 3; ++p) {
        input.dmabuf.offsets[p] = frame.planes[p].dmabufOffset;
        input.dmabuf.strides[p] = frame.planes[p].stride;
    }
    // The lease goes back to the source (and its buffer to the capture queue) when the encoder lets the frame go.
    const void *buffer = lease.get();
    input.owner = std::shared_ptr<void>(const_cast<void *>(buffer), [pool = pool_, lease = std::move(lease)](void *) {
        std::lock_guard lock(pool->mutex);
        --pool->counters.inFlight;
    });
    return input;
}

FeedCounters EncoderFeed::counters() const
{
    std::lock_guard lock(pool_->mutex);
    return pool_->counters;
}

} // namespace overlayd
