// SPDX-License-Identifier: Apache-2.0
// Names of the encoded outputs' choices, for logs, /state and the config's messages.
#include "stream/stream_options.h"

namespace overlayd {

const char *encoderKindName(EncoderKind kind)
{
    switch (kind) {
    case EncoderKind::Auto:
        return "auto";
    case EncoderKind::V4l2:
        return "v4l2";
    case EncoderKind::OpenH264:
        return "openh264";
    case EncoderKind::X264:
        return "x264";
    }
    return "?";
}

const char *profileName(Profile profile)
{
    switch (profile) {
    case Profile::Baseline:
        return "baseline";
    case Profile::Main:
        return "main";
    case Profile::High:
        return "high";
    }
    return "?";
}

const char *codecName(Codec codec)
{
    return codec == Codec::Fwht ? "fwht" : "h264";
}

const char *encodedSinkKindName(EncodedSinkKind kind)
{
    switch (kind) {
    case EncodedSinkKind::Rtsp:
        return "rtsp";
    case EncodedSinkKind::Record:
        return "record";
    case EncodedSinkKind::Push:
        return "push";
    case EncodedSinkKind::File:
        return "file";
    }
    return "?";
}

} // namespace overlayd
