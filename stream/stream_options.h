// SPDX-License-Identifier: Apache-2.0
// What a user configures of the encoded outputs: the one encoder ([encoder]) and the sinks that share its output
// ([[sink]] kind = "rtsp", and the other encoded kinds). Plain data: the config reader fills it, the engine reads it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stream/push_options.h"
#include "stream/record_options.h"
#include "stream/rtsp_access_options.h"
#include "stream/webrtc_options.h"

namespace overlayd {

enum class EncoderKind {
    Auto,     // a V4L2 M2M H.264 encoder when the board has one, else openh264
    V4l2,     // a stateful V4L2 memory-to-memory encoder (v4l2h264enc)
    OpenH264, // software, BSD-licensed
    X264,     // software, GPL: only when asked for and installed
};

enum class Profile { Baseline, Main, High };

// What the encoder makes. FWHT is the codec of the kernel's virtual M2M codec (vicodec): a test codec that nothing
// plays, taken only through the V4L2 encoder path, so that the path a board's H.264 encoder takes is proven on a
// kernel without one.
enum class Codec { H264, Fwht };

// Limits of the [encoder] keys (docs/config.md "Limits").
inline constexpr unsigned kMinBitrateKbps = 64;
inline constexpr unsigned kMaxBitrateKbps = 100000; // 100 Mbit/s: above any H.264 level a board encodes
inline constexpr double kMinKeyframeIntervalSec = 0.1;
inline constexpr double kMaxKeyframeIntervalSec = 60; // a late joiner waits at most this long for a picture
inline constexpr unsigned kMaxQueuedFrames = 8;       // frames in flight towards the encoder ([encoder] queue)

// [encoder] zero_copy: whether a V4L2 encoder is handed the capture buffer by DMABUF instead of a copy.
enum class EncoderZeroCopy { Auto, On, Off };

struct EncoderOptions {
    EncoderKind kind = EncoderKind::Auto;
    Codec codec = Codec::H264;
    std::string device = "auto"; // V4L2: /dev/videoN, or "auto" (the first M2M device that encodes H.264)
    unsigned bitrateKbps = 4000;
    double keyframeIntervalSec = 2.0;
    Profile profile = Profile::Baseline;
    bool lowLatency = true;    // no B-frames, no look-ahead
    unsigned queuedFrames = 3; // frames copied for the encoder and not yet released by it; more are dropped
    EncoderZeroCopy zeroCopy = EncoderZeroCopy::Auto;

    bool operator==(const EncoderOptions &) const = default;
};

// The kinds of [[sink]] that take the encoder's output rather than raw frames.
enum class EncodedSinkKind { Rtsp, Record, Push, File };

// kind = "file": the encoder's elementary stream as it comes (H.264 byte stream, or vicodec's FWHT frames, each
// with its header), in one file: what a decoder driven by hand (v4l2-ctl on vicodec's decoder) reads.
struct FileSinkOptions {
    std::string path;

    bool operator==(const FileSinkOptions &) const = default;
};

// Limits of an RTSP sink (docs/config.md "Limits").
inline constexpr unsigned kMaxRtspClients = 64;
inline constexpr size_t kMaxRtspPathBytes = 256;

struct RtspSinkOptions {
    std::string listen = "127.0.0.1:8554"; // host:port (an IPv6 host in brackets), as the user wrote it
    std::string host = "127.0.0.1";        // numeric, parsed from `listen`
    unsigned port = 8554;
    std::string path = "/stream"; // the mount point: rtsp://host:port/path
    unsigned maxClients = 16;
    RtspAccessOptions access; // credentials and TLS

    bool operator==(const RtspSinkOptions &) const = default;
};

struct EncodedSinkOptions {
    EncodedSinkKind kind = EncodedSinkKind::Rtsp;
    std::string key;          // "sink[2]", for messages
    RtspSinkOptions rtsp;     // kind = "rtsp"
    RecordSinkOptions record; // kind = "record"
    PushSinkOptions push;     // kind = "push"
    FileSinkOptions file;     // kind = "file"

    bool operator==(const EncodedSinkOptions &) const = default;
};

struct StreamOptions {
    EncoderOptions encoder;
    std::vector<EncodedSinkOptions> sinks; // none (and no WebRTC): no encoder runs and GStreamer is never loaded
    WebrtcOptions webrtc;                  // [webrtc] enabled = true runs the encoder alone, with no sink

    bool enabled() const { return !sinks.empty() || webrtc.enabled; }
    bool operator==(const StreamOptions &) const = default;
};

const char *encoderKindName(EncoderKind kind);
const char *profileName(Profile profile);
const char *codecName(Codec codec);
const char *encodedSinkKindName(EncodedSinkKind kind);

// Whether this overlayd was built with the encoded outputs (CMake option OVERLAYD_STREAM, GStreamer).
bool streamBuiltIn();

} // namespace overlayd
