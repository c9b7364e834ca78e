// SPDX-License-Identifier: Apache-2.0
// [webrtc]: read into DaemonConfig::stream.webrtc; enabled alone runs the encoder (no [encoder] table, no encoded
// sink); every bad value refused at its key; WHEP needs the HTTP server.
#include <string>

#include <gtest/gtest.h>

#include "config_test_util.h"
#include "stream/stream_options.h"

namespace overlayd::test {
namespace {

const std::string kHttp = "[http]\nlisten = \"127.0.0.1:8080\"\ncontrol = \"off\"\n";

class WebrtcConfig : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!streamBuiltIn())
            GTEST_SKIP() << "built without the encoded outputs";
    }
};

TEST_F(WebrtcConfig, EnabledAloneRunsTheEncoderWithItsDefaults)
{
    const DaemonConfig config = loadValid(kHttp + "[webrtc]\nenabled = true\n");
    EXPECT_TRUE(config.stream.webrtc.enabled);
    EXPECT_TRUE(config.stream.webrtc.iceServers.empty()); // host candidates only
    EXPECT_EQ(config.stream.webrtc.maxPeers, 8u);
    EXPECT_TRUE(config.stream.sinks.empty());
    EXPECT_TRUE(config.stream.enabled());
    EXPECT_EQ(config.stream.encoder, EncoderOptions{});
}

TEST_F(WebrtcConfig, EveryKey)
{
    const DaemonConfig config = loadValid(kHttp + "[webrtc]\nenabled = true\nmax_peers = 2\nice_servers = "
                                                  "[\"stun://stun.lan:3478\", \"turn://u:p@turn.lan:3478\"]\n");
    EXPECT_EQ(config.stream.webrtc.maxPeers, 2u);
    EXPECT_EQ(config.stream.webrtc.iceServers,
              (std::vector<std::string>{"stun://stun.lan:3478", "turn://u:p@turn.lan:3478"}));
}

TEST_F(WebrtcConfig, DisabledRunsNothing)
{
    const DaemonConfig config = loadValid(kHttp + "[webrtc]\nenabled = false\n");
    EXPECT_FALSE(config.stream.enabled());
}

TEST_F(WebrtcConfig, BadValuesAreRefusedAtTheirKey)
{
    auto problems = loadInvalid(kHttp + "[webrtc]\nenabled = true\nmax_peers = 65\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "webrtc.max_peers");
    EXPECT_EQ(problems[0].line, 6u);
    problems = loadInvalid(kHttp + "[webrtc]\nenabled = true\nice_servers = [\"stun.l.google.com:19302\"]\n");
    EXPECT_TRUE(hasProblem(problems, "webrtc.ice_servers", "\"stun://HOST:PORT\"")) << formatProblems(problems);
    problems = loadInvalid(kHttp + "[webrtc]\nice_servers = [\"stun://a:1\", \"stun://b:2\"]\n");
    EXPECT_TRUE(hasProblem(problems, "webrtc.ice_servers", "one STUN server at most")) << formatProblems(problems);
    problems = loadInvalid(kHttp + "[webrtc]\nenabled = true\nmax_pears = 2\n");
    EXPECT_TRUE(hasProblem(problems, "webrtc.max_pears", "max_peers")) << formatProblems(problems);
}

TEST_F(WebrtcConfig, WhepNeedsTheHttpServer)
{
    const auto problems = loadInvalid("[webrtc]\nenabled = true\n");
    ASSERT_EQ(problems.size(), 1u) << formatProblems(problems);
    EXPECT_EQ(problems[0].key, "webrtc.enabled");
    EXPECT_NE(problems[0].message.find("[http]"), std::string::npos) << problems[0].message;
}

} // namespace
} // namespace overlayd::test
