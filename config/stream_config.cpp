// SPDX-License-Identifier: Apache-2.0
// [encoder] and the encoded kinds of [[sink]] (kind = "rtsp"): every key checked here, the encoder's element asked
// of the engine's module and an RTSP port tried, so that check-config refuses what run would.
#include "config/config_sections.h"

#include <cstdlib>
#include <map>

#include "http/listen_address.h"
#include "stream/engine_loader.h"
#include "stream/listen_check.h"

namespace overlayd {

namespace {

const char *const kBuiltWithout = "this overlayd was built without the encoded outputs (CMake option "
                                  "OVERLAYD_STREAM, GStreamer): ";

void readRtsp(TableReader &sink, RtspSinkOptions &out)
{
    if (auto listen = sink.string("listen")) {
        out.listen = *listen;
        auto address = parseListenAddress(*listen);
        if (!address)
            sink.problem("listen", address.error().message);
        else if (address->kind == ListenAddress::Kind::Unix)
            sink.problem("listen", "an RTSP server listens on HOST:PORT, not a unix socket");
        else if (auto free = checkListenable(address->host, address->port); !free)
            sink.problem("listen", free.error().message);
        else
            out.host = address->host, out.port = address->port;
    }
    if (auto path = sink.string("path", kMaxRtspPathBytes)) {
        const bool valid = path->size() > 1 && path->front() == '/' &&
                           path->find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                   "0123456789-._~/") == std::string::npos &&
                           path->find("//") == std::string::npos && path->back() != '/';
        if (valid)
            out.path = *path;
        else
            sink.problem("path", "'" + *path +
                                     "': a mount point such as \"/cam\": a slash, then letters, digits, "
                                     "'-', '.', '_', '~' and inner slashes");
    }
    if (auto clients = sink.integer("max_clients", 1, kMaxRtspClients))
        out.maxClients = unsigned(*clients);
    readRtspAccess(sink, out.access);
}

// FWHT is encoded by vicodec only, and the encoded sinks so far carry H.264 only (RTP's H.264 payloader, MP4 and
// Matroska muxers that take no FWHT): the file sink writes the stream as the encoder gives it.
void checkFwht(TableReader &table, const StreamOptions &out)
{
    if (out.encoder.kind != EncoderKind::V4l2)
        table.problem("codec", std::string("\"fwht\" is the kernel's test codec (vicodec): only encoder = \"v4l2\" "
                                           "encodes it, not \"") +
                                   encoderKindName(out.encoder.kind) + "\"");
    for (const EncodedSinkOptions &sink : out.sinks)
        if (sink.kind != EncodedSinkKind::File)
            table.problem("codec", "\"fwht\" goes to kind = \"file\" sinks only: " + sink.key + " (kind = \"" +
                                       encodedSinkKindName(sink.kind) + "\") carries H.264");
}

void readFile(TableReader &sink, FileSinkOptions &out)
{
    if (auto path = sink.string("path"); path && !path->empty())
        out.path = *path;
    else if (path)
        sink.problem("path", "empty: the file the encoded stream is written to");
    else
        sink.problem("path", "missing: the file the encoded stream is written to");
}

} // namespace

bool isEncodedSink(TableReader &sink)
{
    const toml::node *kind = sink.node("kind");
    const auto text = kind ? kind->value<std::string>() : std::nullopt;
    return text && (*text == "rtsp" || *text == "record" || *text == "push" || *text == "file");
}

void readEncodedSink(TableReader &sink, StreamOptions &out)
{
    EncodedSinkOptions options;
    options.key = sink.path();
    const std::string kind = sink.string("kind").value_or("rtsp");
    if (!streamBuiltIn()) {
        sink.problem("kind", std::string(kBuiltWithout) + "kind = \"" + kind + "\" is not available");
        sink.ignoreRest();
        return;
    }
    if (kind == "record") {
        options.kind = EncodedSinkKind::Record;
        readRecord(sink, out, options.record);
    } else if (kind == "file") {
        options.kind = EncodedSinkKind::File;
        readFile(sink, options.file);
    } else if (kind == "push") {
        options.kind = EncodedSinkKind::Push;
        readPush(sink, options.push);
    } else {
        options.kind = EncodedSinkKind::Rtsp;
        readRtsp(sink, options.rtsp);
        for (const EncodedSinkOptions &other : out.sinks)
            if (other.kind == EncodedSinkKind::Rtsp && other.rtsp.port == options.rtsp.port)
                sink.problem("listen", "port " + std::to_string(options.rtsp.port) + " is served by " + other.key +
                                           " already: one RTSP sink per port");
    }
    sink.finish();
    out.sinks.push_back(std::move(options));
}

namespace {

// The encoder an encoded sink would start, asked of the engine's module as run would ask it: an element that is not
// installed (x264enc, openh264enc) or no V4L2 M2M encoder is refused at [encoder] encoder.
void checkEncoderThere(TableReader &root, TableReader *table, const StreamOptions &options)
{
    if (!options.enabled())
        return;
    auto there = checkEncoder(options.encoder);
    if (there)
        return;
    if (table) {
        table->problem("encoder", there.error().message);
        return;
    }
    // No [encoder]: the first encoded sink's kind is what asked for one ("sink[2]" is the third [[sink]]).
    const std::string &key = options.sinks.front().key;
    const toml::node *sinks = root.node("sink");
    const toml::array *array = sinks ? sinks->as_array() : nullptr;
    const size_t index = std::strtoul(key.c_str() + key.find('[') + 1, nullptr, 10);
    const toml::table *sink = array && index < array->size() ? (*array)[index].as_table() : nullptr;
    const toml::node *kind = sink ? sink->get("kind") : nullptr;
    const std::string message = "no [encoder], so encoder = \"auto\": " + there.error().message;
    if (kind)
        root.problemAt(*kind, key + ".kind", message);
    else
        root.problem("encoder", message);
}

} // namespace

void readEncoder(TableReader &root, StreamOptions &out)
{
    auto table = root.table("encoder");
    if (!table) {
        if (streamBuiltIn())
            checkEncoderThere(root, nullptr, out);
        return;
    }
    if (!streamBuiltIn()) {
        root.problem("encoder", std::string(kBuiltWithout) + "[encoder] is not available");
        return;
    }
    const size_t before = table->problems().size(); // the element is asked for only when every key was read
    EncoderOptions &encoder = out.encoder;
    if (auto codec = table->choice<Codec>("codec", {{"h264", Codec::H264}, {"fwht", Codec::Fwht}}))
        encoder.codec = *codec;
    if (auto kind = table->choice<EncoderKind>("encoder", {{"auto", EncoderKind::Auto},
                                                           {"v4l2", EncoderKind::V4l2},
                                                           {"openh264", EncoderKind::OpenH264},
                                                           {"x264", EncoderKind::X264}}))
        encoder.kind = *kind;
    if (auto device = table->string("device")) {
        if (*device == "auto" || device->starts_with("/dev/"))
            encoder.device = *device;
        else
            table->problem("device", "'" + *device + "': \"auto\" or a V4L2 device path such as /dev/video11");
        if (encoder.kind != EncoderKind::V4l2 && encoder.kind != EncoderKind::Auto && *device != "auto")
            table->problem("device", std::string("a device is for encoder = \"v4l2\" (or \"auto\"), not \"") +
                                         encoderKindName(encoder.kind) + "\"");
    }
    if (auto bitrate = table->integer("bitrate_kbps", kMinBitrateKbps, kMaxBitrateKbps))
        encoder.bitrateKbps = unsigned(*bitrate);
    if (auto interval = table->number("keyframe_interval_s", kMinKeyframeIntervalSec, kMaxKeyframeIntervalSec))
        encoder.keyframeIntervalSec = *interval;
    if (auto profile = table->choice<Profile>(
            "profile", {{"baseline", Profile::Baseline}, {"main", Profile::Main}, {"high", Profile::High}}))
        encoder.profile = *profile;
    if (auto lowLatency = table->boolean("low_latency"))
        encoder.lowLatency = *lowLatency;
    if (auto queued = table->integer("queue", 1, kMaxQueuedFrames))
        encoder.queuedFrames = unsigned(*queued);
    if (auto zeroCopy = table->choice<EncoderZeroCopy>(
            "zero_copy",
            {{"auto", EncoderZeroCopy::Auto}, {"on", EncoderZeroCopy::On}, {"off", EncoderZeroCopy::Off}})) {
        encoder.zeroCopy = *zeroCopy;
        if (encoder.zeroCopy == EncoderZeroCopy::On && encoder.kind != EncoderKind::V4l2)
            table->problem("zero_copy", std::string("\"on\" needs encoder = \"v4l2\": only a V4L2 M2M encoder imports "
                                                    "the capture buffers (DMABUF), not encoder = \"") +
                                            encoderKindName(encoder.kind) + "\"");
    }
    if (encoder.codec == Codec::Fwht)
        checkFwht(*table, out);
    table->finish();
    if (table->problems().size() == before)
        checkEncoderThere(root, &*table, out);
}

} // namespace overlayd
