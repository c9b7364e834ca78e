// SPDX-License-Identifier: Apache-2.0
// [encoder] and kind = "rtsp" sinks: the documented defaults, every key's refusal at file:line:key, the limits by
// name; built without GStreamer both are refused whole, saying which CMake option.
#include "config_test_util.h"
#include "stream/stream_options.h"

using namespace overlayd;
using overlayd::test::loadInvalid;
using overlayd::test::loadValid;

namespace {

const std::string kBase = test::kMinimalConfig;

bool hasProblem(const std::vector<ConfigProblem> &problems, const std::string &key, const std::string &words)
{
    if (test::hasProblem(problems, key, words))
        return true;
    ADD_FAILURE() << "no problem at " << key << " saying '" << words << "' in:\n" << test::formatProblems(problems);
    return false;
}

const std::string kRtsp = "[[sink]]\nkind = \"rtsp\"\n";

} // namespace

TEST(StreamConfig, WithoutGstreamerBothSectionsAreRefusedSayingWhy)
{
    if (streamBuiltIn())
        GTEST_SKIP() << "built with the encoded outputs";
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + kRtsp), "sink[0].kind", "OVERLAYD_STREAM"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + "[encoder]\n"), "encoder", "OVERLAYD_STREAM"));
}

TEST(StreamConfig, NoEncodedSinkMeansNoEncoder)
{
    EXPECT_FALSE(loadValid(kBase).stream.enabled());
}

TEST(StreamConfig, DefaultsAreTheDocumentedOnes)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    const DaemonConfig config = loadValid(kBase + kRtsp);
    ASSERT_EQ(config.stream.sinks.size(), 1u);
    EXPECT_TRUE(config.sinks.empty()); // an encoded sink is not a raw one
    const EncodedSinkOptions &sink = config.stream.sinks[0];
    EXPECT_EQ(sink.key, "sink[0]");
    EXPECT_EQ(sink.rtsp.listen, "127.0.0.1:8554");
    EXPECT_EQ(sink.rtsp.port, 8554u);
    EXPECT_EQ(sink.rtsp.path, "/stream");
    EXPECT_EQ(config.stream.encoder, EncoderOptions{});
    EXPECT_EQ(config.stream.encoder.kind, EncoderKind::Auto);
    EXPECT_EQ(config.stream.encoder.bitrateKbps, 4000u);
    EXPECT_DOUBLE_EQ(config.stream.encoder.keyframeIntervalSec, 2.0);
}

TEST(StreamConfig, EveryKeyIsRead)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    const DaemonConfig config = loadValid(kBase + R"(
[encoder]
codec = "h264"
encoder = "v4l2"
device = "/dev/video11"
bitrate_kbps = 2500
keyframe_interval_s = 1.5
profile = "high"
low_latency = false
queue = 5
[[sink]]
kind = "y4m"
path = "/dev/null"
[[sink]]
kind = "rtsp"
listen = "0.0.0.0:9554"
path = "/cam/front"
max_clients = 3
)");
    const EncoderOptions &encoder = config.stream.encoder;
    EXPECT_EQ(encoder.kind, EncoderKind::V4l2);
    EXPECT_EQ(encoder.device, "/dev/video11");
    EXPECT_EQ(encoder.bitrateKbps, 2500u);
    EXPECT_DOUBLE_EQ(encoder.keyframeIntervalSec, 1.5);
    EXPECT_EQ(encoder.profile, Profile::High);
    EXPECT_FALSE(encoder.lowLatency);
    EXPECT_EQ(encoder.queuedFrames, 5u);
    ASSERT_EQ(config.sinks.size(), 1u);
    ASSERT_EQ(config.stream.sinks.size(), 1u);
    EXPECT_EQ(config.stream.sinks[0].key, "sink[1]");
    EXPECT_EQ(config.stream.sinks[0].rtsp.host, "0.0.0.0");
    EXPECT_EQ(config.stream.sinks[0].rtsp.port, 9554u);
    EXPECT_EQ(config.stream.sinks[0].rtsp.path, "/cam/front");
    EXPECT_EQ(config.stream.sinks[0].rtsp.maxClients, 3u);
}

TEST(StreamConfig, EveryRefusalIsAtItsKey)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    const auto encoder = [](const std::string &line) {
        return loadInvalid(kBase + kRtsp + "[encoder]\n" + line);
    };
    EXPECT_TRUE(hasProblem(encoder("encoder = \"nvenc\"\n"), "encoder.encoder", "auto | v4l2 | openh264 | x264"));
    EXPECT_TRUE(hasProblem(encoder("codec = \"h265\"\n"), "encoder.codec", "h264"));
    EXPECT_TRUE(hasProblem(encoder("device = \"video11\"\n"), "encoder.device", "/dev/video11"));
    EXPECT_TRUE(hasProblem(encoder("encoder = \"openh264\"\ndevice = \"/dev/video11\"\n"), "encoder.device",
                           "encoder = \"v4l2\""));
    EXPECT_TRUE(hasProblem(encoder("bitrate_kbps = 10\n"), "encoder.bitrate_kbps", "64"));
    EXPECT_TRUE(hasProblem(encoder("bitrate_kbps = 100001\n"), "encoder.bitrate_kbps", "100000"));
    EXPECT_TRUE(hasProblem(encoder("keyframe_interval_s = 61\n"), "encoder.keyframe_interval_s", "60"));
    EXPECT_TRUE(hasProblem(encoder("keyframe_interval_s = 0\n"), "encoder.keyframe_interval_s", "0.1"));
    EXPECT_TRUE(hasProblem(encoder("profile = \"extended\"\n"), "encoder.profile", "baseline | main | high"));
    EXPECT_TRUE(hasProblem(encoder("low_latency = 1\n"), "encoder.low_latency", ""));
    EXPECT_TRUE(hasProblem(encoder("queue = 9\n"), "encoder.queue", "8"));
    EXPECT_TRUE(hasProblem(encoder("bitrate = 5\n"), "encoder.bitrate", "unknown key"));

    const auto rtsp = [](const std::string &lines) {
        return loadInvalid(kBase + kRtsp + lines);
    };
    EXPECT_TRUE(hasProblem(rtsp("listen = \"unix:/tmp/x\"\n"), "sink[0].listen", "HOST:PORT"));
    EXPECT_TRUE(hasProblem(rtsp("listen = \"127.0.0.1:0\"\n"), "sink[0].listen", "1 to 65535"));
    EXPECT_TRUE(hasProblem(rtsp("listen = \"nowhere\"\n"), "sink[0].listen", ""));
    EXPECT_TRUE(hasProblem(rtsp("path = \"cam\"\n"), "sink[0].path", "mount point"));
    EXPECT_TRUE(hasProblem(rtsp("path = \"/cam/\"\n"), "sink[0].path", "mount point"));
    EXPECT_TRUE(hasProblem(rtsp("path = \"/a b\"\n"), "sink[0].path", "mount point"));
    EXPECT_TRUE(hasProblem(rtsp("max_clients = 65\n"), "sink[0].max_clients", "64"));
    EXPECT_TRUE(hasProblem(rtsp("file = \"x\"\n"), "sink[0].file", "unknown key"));
    EXPECT_TRUE(
        hasProblem(loadInvalid(kBase + kRtsp + kRtsp + "path = \"/other\"\n"), "sink[1].listen", "sink[0] already"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + "[[sink]]\nkind = \"rtps\"\n"), "sink[0].kind", "rtsp"));
}

// FWHT is vicodec's codec: the V4L2 encoder only, into kind = "file" sinks only (no payloader or muxer takes it).
TEST(StreamConfig, FwhtIsTheV4l2EncodersIntoAFileOnly)
{
    if (!streamBuiltIn())
        GTEST_SKIP() << "built without the encoded outputs";
    const std::string file = "[[sink]]\nkind = \"file\"\npath = \"/tmp/out.fwht\"\n";
    const auto config = loadValid(kBase + file + "[encoder]\ncodec = \"fwht\"\nencoder = \"v4l2\"\n");
    ASSERT_EQ(config.stream.sinks.size(), 1u);
    EXPECT_EQ(config.stream.sinks[0].kind, EncodedSinkKind::File);
    EXPECT_EQ(config.stream.sinks[0].file.path, "/tmp/out.fwht");
    EXPECT_EQ(config.stream.encoder.codec, Codec::Fwht);
    EXPECT_EQ(config.stream.encoder.kind, EncoderKind::V4l2);
    // An H.264 byte stream goes to a file too.
    EXPECT_EQ(loadValid(kBase + file).stream.encoder.codec, Codec::H264);

    EXPECT_TRUE(hasProblem(loadInvalid(kBase + file + "[encoder]\ncodec = \"fwht\"\n"), "encoder.codec",
                           "only encoder = \"v4l2\" encodes it, not \"auto\""));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + file + "[encoder]\ncodec = \"fwht\"\nencoder = \"openh264\"\n"),
                           "encoder.codec", "not \"openh264\""));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + kRtsp + "[encoder]\ncodec = \"fwht\"\nencoder = \"v4l2\"\n"),
                           "encoder.codec", "sink[0] (kind = \"rtsp\") carries H.264"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + file + "[[sink]]\nkind = \"record\"\ndirectory = \"/tmp/r\"\n" +
                                       "[encoder]\ncodec = \"fwht\"\nencoder = \"v4l2\"\n"),
                           "encoder.codec", "sink[1] (kind = \"record\") carries H.264"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + "[[sink]]\nkind = \"file\"\n"), "sink[0].path", "missing"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + "[[sink]]\nkind = \"file\"\npath = \"\"\n"), "sink[0].path", "empty"));
    EXPECT_TRUE(hasProblem(loadInvalid(kBase + "[[sink]]\nkind = \"file\"\npath = \"x\"\nport = 1\n"), "sink[0].port",
                           "unknown key"));
}
