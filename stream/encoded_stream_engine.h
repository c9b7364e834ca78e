// SPDX-License-Identifier: Apache-2.0
// EncodedStreamEngine: the one encode of the overlaid stream and the encoded sinks that share it. The daemon hands
// it frames already copied (and converted, where needed) into an EncoderInput; an implementation owns everything
// else: the encoder, the RTSP server, its own thread. The GStreamer implementation lives in a module loaded only
// when an encoded sink is configured (engine_loader.h); tests use a fake.
//
// The module boundary: this header and stream_options.h are all the module shares with the binary, and both are
// header-only (but the two name functions, compiled into each side), so the module links nothing of the project.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/result.h"
#include "media/colorimetry.h"
#include "stream/latency_histogram.h"
#include "stream/stream_options.h"
#include "stream/webrtc_peer_stats.h"

namespace overlayd {

// The raw format the engine is fed: always planar I420 (Y, then U, then V, rows packed), converted once by the
// feed (encoder_feed.h) from whatever the stream's format is.
struct EngineFormat {
    unsigned width = 0, height = 0;
    double fps = 0.0; // 0: as frames come (the encoder assumes 30)
    // Frames come as the capture buffers' DMABUF (EncoderInput::dmabuf) rather than copied: a V4L2 encoder imports
    // them (EngineState::dmabufImport says whether it does); another encoder is fed copies as without it.
    bool dmabuf = false;
    Colorimetry colorimetry{}; // of the I420 samples: the stream's, which the feed's conversion keeps

    bool operator==(const EngineFormat &) const = default;
};

// A frame handed by DMABUF: the capture buffer's fd (the source's, kept open by the frame's owner) and where each
// I420 plane starts in it, and its stride. fd -1: the frame is in `data`.
struct DmabufPlanes {
    int fd = -1;
    size_t offsets[3]{};
    unsigned strides[3]{};
};

// One frame for the encoder. `owner` keeps the bytes (or the capture buffer) alive; the engine drops it when the
// encoder is done with the frame (a GStreamer buffer's destroy notify), which gives the slot back to the feed.
struct EncoderInput {
    std::shared_ptr<void> owner;
    const uint8_t *data = nullptr;
    size_t size = 0;
    uint64_t sequence = 0;
    std::chrono::nanoseconds captureTime{0}; // CLOCK_MONOTONIC, when the frame was captured or made
    std::chrono::nanoseconds blendedTime{0}; // CLOCK_MONOTONIC, when the overlay was in it
    DmabufPlanes dmabuf{};                   // fd set: `data` is null, the encoder imports the buffer
};

// One client of an RTSP sink.
struct RtspClientState {
    std::string address;                         // "127.0.0.1:50312"
    std::string transport;                       // "udp", "tcp" (interleaved), "udp-multicast"
    std::chrono::system_clock::time_point since; // when it connected
};

struct EncodedSinkState {
    std::string kind;                     // "rtsp", "record", "push" or "webrtc": which of the fields below it fills
    std::string key;                      // "sink[2]"
    std::string describe;                 // "rtsp://127.0.0.1:8554/cam"
    std::vector<RtspClientState> clients; // kind = "rtsp"
    // kind = "rtsp": connections closed before they asked to play, to make room under PendingClients' caps and at
    // its deadline.
    uint64_t pendingShed = 0;
    uint64_t pendingTimedOut = 0;
    // kind = "webrtc": its peers, and the sums of their statistics since open(), the departed peers' included.
    std::vector<WebrtcPeerState> peers;
    WebrtcPeerStats peerTotals;
    // kind = "record": the segment being written, the finished ones in the directory, their bytes, the oldest,
    // how many retention deleted; stopped for a full disk (and how often it was).
    std::string currentFile;
    unsigned segments = 0;
    uint64_t bytes = 0;
    std::string oldest;
    unsigned deleted = 0;
    bool diskFull = false;
    unsigned diskFullStops = 0;
    // kind = "push": the server takes the stream; attempts after the first.
    bool connected = false;
    unsigned reconnects = 0;
    // record and push: the last failure (empty when none); access units dropped while behind or not running.
    std::string lastError;
    uint64_t dropped = 0;
};

// What /state and /metrics show. Counters count from open().
struct EngineState {
    bool running = false;
    std::string encoder;        // the element that encodes: "openh264enc", "x264enc", "v4l2h264enc"
    std::string device;         // the V4L2 encoder's device, empty for software
    bool dmabufImport = false;  // the encoder imports the frames' DMABUF (EngineFormat::dmabuf and a V4L2 encoder)
    uint64_t framesIn = 0;      // frames handed to the encoder
    uint64_t framesEncoded = 0; // access units out of the encoder
    uint64_t keyframes = 0;
    uint64_t bytesEncoded = 0;
    double bitrateKbps = 0; // measured over the last second's access units
    std::vector<EncodedSinkState> sinks;
    // From the frame's blend (EncoderInput::blendedTime) to: "encoder_in" (handed to the encoder), "encoded" (its
    // access unit out), "sent" (handed to an RTSP media, the last step before its sockets).
    std::vector<std::pair<std::string, LatencyHistogram>> latency;
};

// A WebRTC peer's answer: the id DELETE /whep/ID hangs up, and the SDP (with the engine's ICE candidates).
struct WebrtcAnswer {
    std::string id;
    std::string sdp;
};

// How the engine reports (from its own thread): a line for the daemon's log, at a syslog priority.
using EngineLog = std::function<void(int level, const std::string &message)>;
inline constexpr int kLogError = 3, kLogWarning = 4, kLogNotice = 5, kLogInfo = 6, kLogDebug = 7;

class EncodedStreamEngine
{
public:
    virtual ~EncodedStreamEngine() = default;

    // Builds and starts the encoder and every encoded sink for frames of `format`; the RTSP servers listen from
    // here on. Called again when the stream's format changes (the old pipeline closes first).
    virtual Status open(const EngineFormat &format) = 0;
    // Never blocks: the frame is queued for the encoder's thread. The feed bounds how many are in flight.
    virtual void push(EncoderInput frame) = 0;
    // Stops the encoder and the sinks (clients are disconnected); safe to call twice.
    virtual void close() = 0;

    virtual EngineState state() const = 0;

    // WebRTC ([webrtc] enabled): a peer for an SDP offer, answered once the engine's ICE candidates are gathered
    // (waiting at most kWhepAnswerTimeout). Errors: Malformed (the offer; the message says what is wrong), TryAgain
    // (max_peers reached, or no stream yet), DeviceLost (no answer in time), Unsupported (WebRTC is off).
    virtual Result<WebrtcAnswer> addPeer(const std::string &offer, const std::string &address)
    {
        (void)offer, (void)address;
        return makeError(ErrorCode::Unsupported, "WebRTC is off ([webrtc] enabled = true turns it on)");
    }
    // Hangs the peer up; NotFound when there is none of that id.
    virtual Status removePeer(const std::string &id) { return makeError(ErrorCode::NotFound, "no WebRTC peer " + id); }
};

// The module's one entry point (extern "C", looked up by name): a new engine for the options, or null with the
// reason in `error`. `log` outlives the engine.
using CreateEngineFunction = EncodedStreamEngine *(*)(const StreamOptions *options, const EngineLog *log,
                                                      std::string *error);
inline constexpr const char *kCreateEngineSymbol = "overlayd_stream_create_engine";
// Its second: whether the encoder the options ask for is there (the element installed, a V4L2 M2M encoder present),
// false with the reason in `error`; for the config loader, so that check-config refuses what run would.
using CheckEncoderFunction = bool (*)(const EncoderOptions *options, std::string *error);
inline constexpr const char *kCheckEncoderSymbol = "overlayd_stream_check_encoder";
// Its third: whether GLib can serve RTSPS with this certificate and key (PEM): a TLS backend (glib-networking) is
// installed and takes them, as the RTSP server will; false with the reason in `error`.
using CheckTlsFunction = bool (*)(const std::string *certPem, const std::string *keyPem, std::string *error);
inline constexpr const char *kCheckTlsSymbol = "overlayd_stream_check_tls";
// The module's file name, next to the binary in the build tree or in the library folder when installed.
inline constexpr const char *kModuleFileName = "overlayd-stream.so";
// Where the Debian package puts the module, relative to the binary's folder (/usr/bin -> /usr/lib/overlayd), looked
// in after the binary's own folder (the build tree) and before OVERLAYD_STREAM_MODULE_DIR (cmake --install).
inline constexpr const char *kPackagedModuleDir = "../lib/overlayd";

} // namespace overlayd
