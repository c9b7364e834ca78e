// SPDX-License-Identifier: Apache-2.0
// BranchFeed: the mutex guards the appsrc against attach/detach on the main loop thread while push() runs on the
// encoder's streaming thread; pushing into an appsrc never blocks (block = false), so holding it is short.
#include "stream/gst/branch_feed.h"

#include <gst/app/gstappsrc.h>

#include "stream/fwht_header.h"

namespace overlayd {
namespace {

bool isFwhtKeyframe(GstBuffer *buffer)
{
    uint8_t header[kFwhtHeaderBytes];
    const gsize copied = gst_buffer_extract(buffer, 0, header, sizeof(header));
    return fwhtIsKeyframe(header, copied);
}

} // namespace

BranchFeed::BranchFeed(std::function<void()> requestKeyframe, bool fwht)
    : requestKeyframe_(std::move(requestKeyframe)), fwht_(fwht)
{}

BranchFeed::~BranchFeed()
{
    detach();
}

void BranchFeed::attach(GstElement *appsrc)
{
    {
        std::lock_guard lock(mutex_);
        if (appsrc_ != nullptr)
            gst_object_unref(appsrc_);
        appsrc_ = GST_ELEMENT(gst_object_ref(appsrc));
        waitingForKeyframe_ = true;
        offset_ = GST_CLOCK_TIME_NONE;
    }
    requestKeyframe_(); // the branch starts with the next frame, not the next interval
}

void BranchFeed::detach()
{
    std::lock_guard lock(mutex_);
    if (appsrc_ != nullptr)
        gst_object_unref(appsrc_);
    appsrc_ = nullptr;
}

void BranchFeed::endOfStream()
{
    std::lock_guard lock(mutex_);
    if (appsrc_ == nullptr)
        return;
    gst_app_src_end_of_stream(GST_APP_SRC(appsrc_));
    gst_object_unref(appsrc_);
    appsrc_ = nullptr;
}

uint64_t BranchFeed::dropped() const
{
    std::lock_guard lock(mutex_);
    return dropped_;
}

bool BranchFeed::push(GstSample *sample)
{
    GstBuffer *buffer = gst_sample_get_buffer(sample);
    bool askKeyframe = false, pushed = false;
    {
        std::lock_guard lock(mutex_);
        if (appsrc_ == nullptr || buffer == nullptr)
            return false;
        const bool keyframe =
            fwht_ ? isFwhtKeyframe(buffer) : !GST_BUFFER_FLAG_IS_SET(buffer, GST_BUFFER_FLAG_DELTA_UNIT);
        if (gst_app_src_get_current_level_buffers(GST_APP_SRC(appsrc_)) >= kBranchBacklogBuffers) {
            askKeyframe = !waitingForKeyframe_;
            waitingForKeyframe_ = true;
        }
        if (waitingForKeyframe_ && !keyframe) {
            ++dropped_;
        } else {
            waitingForKeyframe_ = false;
            if (!GST_CLOCK_TIME_IS_VALID(offset_))
                offset_ = GST_BUFFER_DTS_IS_VALID(buffer) ? GST_BUFFER_DTS(buffer) : GST_BUFFER_PTS(buffer);
            GstBuffer *shifted = gst_buffer_copy(buffer); // the metadata only: the memory is shared
            for (GstClockTime *time : {&GST_BUFFER_PTS(shifted), &GST_BUFFER_DTS(shifted)})
                if (GST_CLOCK_TIME_IS_VALID(*time))
                    *time = *time > offset_ ? *time - offset_ : 0;
            GstSample *moved = gst_sample_new(shifted, gst_sample_get_caps(sample), nullptr, nullptr);
            gst_buffer_unref(shifted);
            pushed = gst_app_src_push_sample(GST_APP_SRC(appsrc_), moved) == GST_FLOW_OK;
            gst_sample_unref(moved);
        }
    }
    if (askKeyframe)
        requestKeyframe_();
    return pushed;
}

} // namespace overlayd
