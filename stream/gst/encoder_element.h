// SPDX-License-Identifier: Apache-2.0
// The encoder element for the options: a V4L2 M2M encoder (v4l2*h264enc, one element per device), openh264enc or
// x264enc, with the bitrate, keyframe interval and latency settings in each one's own property names.
#pragma once

#include <gst/gst.h>

#include <string>

#include "base/result.h"
#include "stream/stream_options.h"

namespace overlayd {

struct EncoderElement {
    GstElement *element = nullptr; // floating: the bin that adds it takes it
    std::string factory;           // "openh264enc"
    std::string device;            // the V4L2 encoder's device node, empty for software
    GstCaps *outputCaps = nullptr; // the profile asked for, to filter the encoder's output (owned by the caller)
};

Result<EncoderElement> makeEncoderElement(const EncoderOptions &options, double fps);

} // namespace overlayd
