// SPDX-License-Identifier: Apache-2.0
// makeEncoderElement: auto takes the first V4L2 M2M H.264 encoder the registry knows (the v4l2 plugin registers
// one element per encoder device it finds), else openh264. FWHT (vicodec) comes through the same V4L2 path.
#include "stream/gst/encoder_element.h"

#include <cmath>

namespace overlayd {
namespace {

// The v4l2 plugin's encoders of `codec`: "v4l2h264enc" (or "v4l2fwhtenc") for the first device,
// "v4l2videoNh264enc" for others.
std::vector<std::string> v4l2EncoderFactories(Codec codec)
{
    const std::string suffix = std::string(codecName(codec)) + "enc";
    std::vector<std::string> names;
    GList *factories = gst_element_factory_list_get_elements(GST_ELEMENT_FACTORY_TYPE_ENCODER, GST_RANK_NONE);
    for (GList *item = factories; item != nullptr; item = item->next) {
        const std::string name = gst_plugin_feature_get_name(GST_PLUGIN_FEATURE(item->data));
        if (name.starts_with("v4l2") && name.ends_with(suffix))
            names.push_back(name);
    }
    gst_plugin_feature_list_free(factories);
    return names;
}

std::string deviceOf(GstElement *element)
{
    gchar *device = nullptr;
    g_object_get(element, "device", &device, nullptr);
    std::string text = device ? device : "";
    g_free(device);
    return text;
}

Result<EncoderElement> makeV4l2(const EncoderOptions &options, unsigned gop)
{
    const std::string what = std::string("V4L2 M2M ") + (options.codec == Codec::Fwht ? "FWHT" : "H.264") + " encoder";
    for (const std::string &name : v4l2EncoderFactories(options.codec)) {
        GstElement *element = gst_element_factory_make(name.c_str(), nullptr);
        if (element == nullptr)
            continue;
        gst_object_ref_sink(element);
        const std::string device = deviceOf(element);
        if (options.device != "auto" && device != options.device) {
            gst_object_unref(element);
            continue;
        }
        // The stateful H.264 encoders' controls (bcm2835-codec, the Rockchip and Amlogic ones take these); vicodec
        // has no bitrate, its picture group is the generic GOP size.
        const std::string controls = options.codec == Codec::Fwht
                                         ? "controls,video_gop_size=" + std::to_string(gop)
                                         : "controls,video_bitrate=" + std::to_string(options.bitrateKbps * 1000) +
                                               ",h264_i_frame_period=" + std::to_string(gop) +
                                               ",repeat_sequence_header=1";
        GstStructure *structure = gst_structure_from_string(controls.c_str(), nullptr);
        g_object_set(element, "extra-controls", structure, nullptr);
        gst_structure_free(structure);
        EncoderElement out{element, name, device, nullptr};
        g_object_force_floating(G_OBJECT(element)); // back to floating: the bin takes it
        return out;
    }
    return makeError(ErrorCode::NotFound, options.device == "auto"
                                              ? "no " + what + " on this machine (GStreamer's v4l2 plugin lists none)"
                                              : "no " + what + " at " + options.device);
}

} // namespace

Result<EncoderElement> makeEncoderElement(const EncoderOptions &options, double fps)
{
    const double rate = fps > 0 ? fps : 30.0;
    // The engine forces keyframes every keyframe_s by the frames' times; the encoder's own count of frames is a
    // fallback set past it, so that at the nominal rate the two never place keyframes a frame apart.
    const unsigned gop = std::max(2u, unsigned(std::lround(2 * options.keyframeIntervalSec * rate)));
    EncoderElement out;
    if (options.kind == EncoderKind::V4l2 || options.kind == EncoderKind::Auto) {
        auto v4l2 = makeV4l2(options, gop);
        if (v4l2 || options.kind == EncoderKind::V4l2)
            out = v4l2 ? *v4l2 : EncoderElement{};
        if (!v4l2 && options.kind == EncoderKind::V4l2)
            return v4l2.error();
    }
    if (out.element == nullptr && options.kind == EncoderKind::X264) {
        out.element = gst_element_factory_make("x264enc", nullptr);
        if (out.element == nullptr)
            return makeError(ErrorCode::NotFound, "encoder = \"x264\": the x264enc element is not installed "
                                                  "(Debian: gstreamer1.0-plugins-ugly)");
        out.factory = "x264enc";
        g_object_set(out.element, "bitrate", guint(options.bitrateKbps), "key-int-max", guint(gop), nullptr);
        if (options.lowLatency) // zerolatency: no B-frames, no look-ahead, no frame threads
            gst_util_set_object_arg(G_OBJECT(out.element), "tune", "zerolatency");
        gst_util_set_object_arg(G_OBJECT(out.element), "speed-preset", "veryfast");
    }
    if (out.element == nullptr) {
        out.element = gst_element_factory_make("openh264enc", nullptr);
        if (out.element == nullptr)
            return makeError(ErrorCode::NotFound, "the openh264enc element is not installed (Debian: "
                                                  "gstreamer1.0-plugins-bad and libopenh264-7)");
        out.factory = "openh264enc";
        // openh264 has no B-frames: every frame leaves before the next arrives, low_latency or not.
        g_object_set(out.element, "bitrate", guint(options.bitrateKbps * 1000), "gop-size", guint(gop), nullptr);
        gst_util_set_object_arg(G_OBJECT(out.element), "rate-control", "bitrate");
        gst_util_set_object_arg(G_OBJECT(out.element), "usage-type", "camera");
    }
    // openh264 encodes constrained baseline only; the others are told the profile through their output caps. FWHT
    // has no profiles.
    if (out.factory != "openh264enc" && options.codec == Codec::H264)
        out.outputCaps = gst_caps_new_simple(
            "video/x-h264", "profile", G_TYPE_STRING,
            options.profile == Profile::Baseline ? "constrained-baseline" : profileName(options.profile), nullptr);
    return out;
}

} // namespace overlayd
