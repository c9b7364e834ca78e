// SPDX-License-Identifier: Apache-2.0
// SystemdNotifier against a real AF_UNIX datagram socket: the exact sd_notify messages, and silence without one.
#include "daemon/systemd_notify.h"

#include <cstdlib>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>

#include "notify_socket.h"

namespace overlayd {
namespace {

using namespace std::chrono_literals;
using test::NotifySocket;
using test::TempDir;

// Each test starts from an environment without systemd's variables and restores nothing: the variables are ours.
class NotifierTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        for (const char *name : {"NOTIFY_SOCKET", "WATCHDOG_USEC", "WATCHDOG_PID"})
            unsetenv(name);
        if (!OVERLAYD_TEST_HAVE_LIBSYSTEMD)
            GTEST_SKIP() << "built with OVERLAYD_SYSTEMD=OFF: the notifier is the no-op one";
        ASSERT_FALSE(dir_.path().empty());
        ASSERT_TRUE(socket_.ok()) << socket_.path();
        setenv("NOTIFY_SOCKET", socket_.path().c_str(), 1);
    }
    void TearDown() override { unsetenv("NOTIFY_SOCKET"); }

    std::string next()
    {
        auto datagram = socket_.receive(2000ms);
        if (!datagram)
            return "<nothing>";
        EXPECT_EQ(datagram->pid, getpid()) << "systemd (NotifyAccess=main) checks the sender's pid";
        return datagram->text;
    }

    TempDir dir_;
    NotifySocket socket_{dir_.path() / "notify"};
};

TEST_F(NotifierTest, SendsEachStateAsOneDatagram)
{
    auto notifier = SystemdNotifier::fromEnvironment();
    ASSERT_TRUE(notifier->active());
    notifier->ready();
    notifier->watchdog();
    notifier->stopping();
    EXPECT_EQ(next(), "READY=1");
    EXPECT_EQ(next(), "WATCHDOG=1");
    EXPECT_EQ(next(), "STOPPING=1");
    EXPECT_FALSE(socket_.receive(50ms)) << "one datagram per call, nothing more";
}

TEST_F(NotifierTest, ReloadingCarriesTheMonotonicClock)
{
    auto notifier = SystemdNotifier::fromEnvironment();
    uint64_t before = test::monotonicMicroseconds();
    notifier->reloading();
    uint64_t after = test::monotonicMicroseconds();
    auto datagram = socket_.receive(2000ms);
    ASSERT_TRUE(datagram);
    auto fields = datagram->fields();
    EXPECT_EQ(fields["RELOADING"], "1");
    ASSERT_TRUE(fields.count("MONOTONIC_USEC")) << datagram->text;
    uint64_t stamp = std::stoull(fields["MONOTONIC_USEC"]);
    EXPECT_GE(stamp, before);
    EXPECT_LE(stamp, after);
}

TEST_F(NotifierTest, StatusIsOneLine)
{
    auto notifier = SystemdNotifier::fromEnvironment();
    notifier->status("streaming 1280x720 YUYV 30.0 fps, 0 drops");
    notifier->status("first\nsecond\r\nthird");
    EXPECT_EQ(next(), "STATUS=streaming 1280x720 YUYV 30.0 fps, 0 drops");
    EXPECT_EQ(next(), "STATUS=first second  third");
}

TEST_F(NotifierTest, ExtendTimeoutInMicroseconds)
{
    auto notifier = SystemdNotifier::fromEnvironment();
    notifier->extendTimeout(std::chrono::seconds(8));
    EXPECT_EQ(next(), "EXTEND_TIMEOUT_USEC=8000000");
}

TEST_F(NotifierTest, WatchdogIntervalIsHalfOfWatchdogUsec)
{
    setenv("WATCHDOG_USEC", "3000000", 1);
    EXPECT_EQ(SystemdNotifier::fromEnvironment()->watchdogInterval(), std::chrono::microseconds(1500000));
    setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
    EXPECT_EQ(SystemdNotifier::fromEnvironment()->watchdogInterval(), std::chrono::microseconds(1500000));
}

TEST_F(NotifierTest, NoWatchdogWhenNotOursOrNotSet)
{
    EXPECT_FALSE(SystemdNotifier::fromEnvironment()->watchdogInterval()) << "no WATCHDOG_USEC";
    setenv("WATCHDOG_USEC", "3000000", 1);
    setenv("WATCHDOG_PID", std::to_string(getpid() + 1).c_str(), 1);
    EXPECT_FALSE(SystemdNotifier::fromEnvironment()->watchdogInterval()) << "the watchdog is another process's";
    unsetenv("WATCHDOG_PID");
    setenv("WATCHDOG_USEC", "soon", 1);
    EXPECT_FALSE(SystemdNotifier::fromEnvironment()->watchdogInterval()) << "unparsable WATCHDOG_USEC";
}

TEST_F(NotifierTest, SilentAndHarmlessWithoutNotifySocket)
{
    unsetenv("NOTIFY_SOCKET");
    setenv("WATCHDOG_USEC", "3000000", 1);
    auto notifier = SystemdNotifier::fromEnvironment();
    EXPECT_FALSE(notifier->active());
    EXPECT_FALSE(notifier->watchdogInterval()) << "nobody to pet";
    notifier->ready();
    notifier->reloading();
    notifier->status("nobody listens");
    notifier->watchdog();
    notifier->stopping();
    EXPECT_FALSE(socket_.receive(100ms));
}

TEST_F(NotifierTest, UnreachableSocketDoesNotFail)
{
    setenv("NOTIFY_SOCKET", (dir_.path() / "nobody-here").c_str(), 1);
    auto notifier = SystemdNotifier::fromEnvironment();
    notifier->ready();
    notifier->watchdog();
    notifier->stopping();
    EXPECT_FALSE(socket_.receive(100ms));
}

// Both builds: the notifier is live exactly when libsystemd is compiled in; a compiled-out one sends nothing even
// with NOTIFY_SOCKET set.
TEST(NotifierBuild, ActiveExactlyWhenCompiledIn)
{
    TempDir dir;
    NotifySocket socket(dir.path() / "notify");
    ASSERT_TRUE(socket.ok());
    setenv("NOTIFY_SOCKET", socket.path().c_str(), 1);
    auto notifier = SystemdNotifier::fromEnvironment();
    notifier->ready();
    unsetenv("NOTIFY_SOCKET");
    EXPECT_EQ(notifier->active(), bool(OVERLAYD_TEST_HAVE_LIBSYSTEMD));
    EXPECT_EQ(socket.receive(200ms).has_value(), bool(OVERLAYD_TEST_HAVE_LIBSYSTEMD));
}

} // namespace
} // namespace overlayd
