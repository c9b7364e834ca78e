// SPDX-License-Identifier: Apache-2.0
// What flows between a source, the blender and the sinks: the stream's format, each frame's metadata, and the
// lease through which a source lends a frame's memory to the pipeline.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "media/colorimetry.h"
#include "media/frame.h"
#include "media/pixel_format.h"

namespace overlayd {

// A stream's negotiated format. stride is plane 0's bytesperline (0: rows packed); fps 0 means "as fast as
// frames come" (replay under `overlayd render`).
struct StreamFormat {
    const PixelFormatInfo *format = nullptr;
    unsigned width = 0, height = 0;
    unsigned stride = 0;
    Colorimetry colorimetry{};
    double fps = 0.0;
    // Frames are leases of this many dmabuf-exported buffers (PlaneView::dmabufFd set); 0: no dmabuf fds. A
    // zero-copy sink may hold up to dmabufBuffers - 2 of them, so that the source keeps two to capture into.
    unsigned dmabufBuffers = 0;

    // A different stream in any respect: the sinks re-open for it.
    bool operator==(const StreamFormat &) const = default;

    // "1280x720 YUYV 30.0 fps", for logs and systemd STATUS=.
    std::string describe() const;
};

struct FrameMetadata {
    uint64_t sequence = 0;                             // counts from 0; a gap means the source dropped frames
    std::chrono::nanoseconds timestamp{0};             // CLOCK_MONOTONIC, when the frame was captured or made
    std::chrono::system_clock::time_point wallClock{}; // for timestamp text on the overlay
    Colorimetry colorimetry{};
    // What the camera reports of how the frame was exposed (libcamera cameras); absent elsewhere.
    std::optional<int32_t> exposureUs;
    std::optional<float> analogueGain;
};

// Whoever lends frames out by index (a source's buffer pool): a lease that ends gives its index back here.
class LeaseOwner
{
public:
    virtual ~LeaseOwner() = default;
    virtual void giveBack(unsigned index) = 0;
};

// A frame lent by its source. Destroying (or resetting) the lease gives the buffer back; the view stays valid
// until then. Move-only, so exactly one owner returns it.
class FrameLease
{
public:
    FrameLease() = default;
    // The sources' form: the lease keeps its owner alive, and making one allocates nothing (a std::function holding
    // a shared_ptr would allocate every frame).
    FrameLease(FrameView view, FrameMetadata metadata, std::shared_ptr<LeaseOwner> owner, unsigned index)
        : view_(view), metadata_(metadata), owner_(std::move(owner)), index_(index)
    {}
    FrameLease(FrameView view, FrameMetadata metadata, std::function<void()> giveBack)
        : view_(view), metadata_(metadata), giveBack_(std::move(giveBack))
    {}
    FrameLease(FrameLease &&other) noexcept { *this = std::move(other); }
    FrameLease &operator=(FrameLease &&other) noexcept
    {
        if (this != &other) {
            reset();
            view_ = other.view_;
            metadata_ = other.metadata_;
            giveBack_ = std::exchange(other.giveBack_, nullptr);
            owner_ = std::move(other.owner_);
            index_ = other.index_;
        }
        return *this;
    }
    FrameLease(const FrameLease &) = delete;
    FrameLease &operator=(const FrameLease &) = delete;
    ~FrameLease() { reset(); }

    void reset()
    {
        if (giveBack_)
            std::exchange(giveBack_, nullptr)();
        if (owner_)
            std::exchange(owner_, nullptr)->giveBack(index_);
    }

    const FrameView &view() const { return view_; }
    const FrameMetadata &metadata() const { return metadata_; }
    FrameMetadata &metadata() { return metadata_; }

private:
    FrameView view_{};
    FrameMetadata metadata_{};
    std::function<void()> giveBack_;
    std::shared_ptr<LeaseOwner> owner_;
    unsigned index_ = 0;
};

} // namespace overlayd
