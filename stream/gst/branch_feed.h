// SPDX-License-Identifier: Apache-2.0
// BranchFeed: hands the encoder's access units to the appsrc of a pipeline of its own (a recording's, a push's), so
// that a branch that fails, blocks or is rebuilt never touches the encoder pipeline. Each new appsrc starts at a
// keyframe with its timeline at 0; a branch that falls behind drops up to the next keyframe rather than stall or
// feed a decoder a hole in the middle of a picture group.
#pragma once

#include <gst/gst.h>

#include <cstdint>
#include <functional>
#include <mutex>

namespace overlayd {

// Access units waiting in a branch's appsrc beyond this are dropped up to the next keyframe (a few seconds of
// video at 30 fps: a stalled disk or socket, not jitter).
inline constexpr guint64 kBranchBacklogBuffers = 90;

class BranchFeed
{
public:
    // `fwht`: keyframes are read from each frame's FWHT header (vicodec flags none of its encoded buffers).
    explicit BranchFeed(std::function<void()> requestKeyframe, bool fwht = false);
    ~BranchFeed();
    BranchFeed(const BranchFeed &) = delete;
    BranchFeed &operator=(const BranchFeed &) = delete;

    // From now on access units go to `appsrc` (a reference is taken), starting at the next keyframe.
    void attach(GstElement *appsrc);
    // Access units are dropped until the next attach().
    void detach();
    // On the encoder's streaming thread; never blocks. True when the access unit went into the appsrc (false while
    // detached or waiting for a keyframe).
    bool push(GstSample *sample);
    // Sends end-of-stream into the attached appsrc (the muxer finishes its file), then detaches.
    void endOfStream();

    uint64_t dropped() const;

private:
    std::function<void()> requestKeyframe_;
    bool fwht_ = false;
    mutable std::mutex mutex_;
    GstElement *appsrc_ = nullptr;
    bool waitingForKeyframe_ = true;
    GstClockTime offset_ = GST_CLOCK_TIME_NONE; // the encoder's time of the branch's first access unit
    uint64_t dropped_ = 0;
};

} // namespace overlayd
