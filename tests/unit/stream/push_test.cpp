// SPDX-License-Identifier: Apache-2.0
// Push URLs and the reconnect state.
#include "stream/push_link.h"
#include "stream/push_options.h"

#include <gtest/gtest.h>

namespace overlayd {
namespace {

using std::chrono::milliseconds;

TEST(PushUrl, TheSchemePicksTheProtocol)
{
    std::string why;
    EXPECT_EQ(pushProtocol("rtsp://127.0.0.1:8554/cam", why), PushProtocol::Rtsp);
    EXPECT_EQ(pushProtocol("rtmp://media.example/live/key", why), PushProtocol::Rtmp);
    EXPECT_EQ(pushProtocol("srt://[::1]:9000?streamid=cam", why), PushProtocol::Srt);
    EXPECT_EQ(protocolName(PushProtocol::Srt), "srt");
}

TEST(PushUrl, OthersAreRefusedWithTheReason)
{
    std::string why;
    EXPECT_FALSE(pushProtocol("http://127.0.0.1/cam", why));
    EXPECT_EQ(why, "the scheme 'http' cannot be pushed to: rtsp://, rtmp:// or srt://");
    EXPECT_FALSE(pushProtocol("RTSP://host/cam", why)); // the elements take lower-case schemes only
    EXPECT_FALSE(pushProtocol("127.0.0.1:8554", why));
    EXPECT_EQ(why, "not a URL: expected rtsp://, rtmp:// or srt:// and a host");
    EXPECT_FALSE(pushProtocol("rtmp:///live", why));
    EXPECT_EQ(why, "no host after rtmp://");
    EXPECT_FALSE(pushProtocol("srt://:9000", why));
}

TEST(PushLink, BacksOffWhileDownAndStartsOverAfterAConnection)
{
    PushLink link(Backoff(milliseconds(500), milliseconds(2000)));
    EXPECT_FALSE(link.isConnected());
    auto retry = link.failed("connection refused");
    EXPECT_EQ(retry.delay, milliseconds(500));
    EXPECT_TRUE(retry.newReason);
    link.retrying();
    retry = link.failed("connection refused");
    EXPECT_EQ(retry.delay, milliseconds(1000));
    EXPECT_FALSE(retry.newReason); // the same reason again: not logged again
    link.retrying();
    EXPECT_EQ(link.failed("connection refused").delay, milliseconds(2000));
    link.retrying();
    EXPECT_EQ(link.failed("connection refused").delay, milliseconds(2000)); // the ceiling
    link.retrying();
    EXPECT_EQ(link.reconnects(), 4u);
    link.connected();
    EXPECT_TRUE(link.isConnected());
    EXPECT_TRUE(link.lastError().empty());
    retry = link.failed("connection reset");
    EXPECT_FALSE(link.isConnected());
    EXPECT_EQ(retry.delay, milliseconds(500));
    EXPECT_TRUE(retry.newReason);
    EXPECT_EQ(link.lastError(), "connection reset");
}

} // namespace
} // namespace overlayd
