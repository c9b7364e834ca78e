// SPDX-License-Identifier: Apache-2.0
// The real overlayd binary talking to a notify socket owned by the test, as systemd would see it: READY after the
// first frame, WATCHDOG only while frames flow, RELOADING/READY around SIGHUP, STOPPING on SIGTERM.
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "daemon_process.h"
#include "notify_socket.h"

namespace overlayd {
namespace {

using namespace std::chrono_literals;
using test::Datagram;

// Pinned config keys only; colour bars need no [camera]. 320x240 keeps the daemon cheap on a loaded machine.
std::string syntheticConfig(unsigned width, unsigned stallAfterFrames)
{
    return "[daemon]\nlog_level = \"info\"\nstats_interval = 0.0\n"
           "[source]\nkind = \"synthetic\"\nformat = \"YUYV\"\nwidth = " +
           std::to_string(width) +
           "\nheight = 240\nfps = 30.0\n"
           "[source.synthetic]\npattern = \"colour-bars\"\nstall_after_frames = " +
           std::to_string(stallAfterFrames) + "\n[[sink]]\nkind = \"null\"\n";
}

constexpr const char *watchdogUsec = "400000"; // the daemon should pet every 200 ms

class DaemonNotifyTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!OVERLAYD_TEST_HAVE_LIBSYSTEMD)
            GTEST_SKIP() << "built with OVERLAYD_SYSTEMD=OFF: the daemon cannot notify";
        if (const char *other = std::getenv("OVERLAYD_TEST_DAEMON"))
            binary_ = other;
        ASSERT_NE(binary_, "") << "the overlayd target does not exist yet (daemon/CMakeLists.txt): these "
                                  "tests need the real daemon and must not pass without it";
        ASSERT_TRUE(socket_.ok());
    }

    void TearDown() override
    {
        if (!HasFailure() || !daemon_)
            return;
        std::cout << "datagrams received:\n";
        for (const auto &d : history_)
            std::cout << "  [" << d.receivedUsec << " pid " << d.pid << "] " << d.text << "\n";
        if (daemon_)
            std::cout << "daemon output:\n" << daemon_->log();
    }

    std::filesystem::path writeConfig(const std::string &text)
    {
        std::filesystem::path path = dir_.path() / "camera.toml";
        std::ofstream(path) << text;
        return path;
    }

    void start(const std::string &config, bool withSocket = true)
    {
        std::map<std::string, std::string> environment{{"WATCHDOG_USEC", watchdogUsec}};
        if (withSocket)
            environment["NOTIFY_SOCKET"] = socket_.path().string();
        daemon_ = std::make_unique<test::DaemonProcess>(
            binary_, std::vector<std::string>{"run", "--config", writeConfig(config).string()}, environment,
            dir_.path() / "daemon.log");
        ASSERT_TRUE(daemon_->started());
    }

    // Receives until a datagram carries `key`; every datagram goes into history_ and must come from the daemon's
    // main process (NotifyAccess=main would drop anything else).
    std::optional<Datagram> waitFor(const std::string &key, std::chrono::milliseconds timeout)
    {
        auto end = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < end) {
            auto d = socket_.receive(
                std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now() + 1ms));
            if (!d)
                break;
            record(*d);
            if (d->has(key))
                return d;
        }
        return std::nullopt;
    }

    std::vector<Datagram> collect(std::chrono::milliseconds duration)
    {
        auto received = socket_.collect(duration);
        for (const auto &d : received)
            record(d);
        return received;
    }

    void record(const Datagram &d)
    {
        history_.push_back(d);
        EXPECT_EQ(d.pid, daemon_->pid()) << "sent by another process: " << d.text;
    }

    // SIGTERM: STOPPING=1, then a clean exit.
    void stopCleanly()
    {
        daemon_->signal(SIGTERM);
        EXPECT_TRUE(waitFor("STOPPING", 10s)) << "no STOPPING=1 after SIGTERM";
        auto status = daemon_->wait(15s);
        ASSERT_TRUE(status) << "still running 15 s after SIGTERM";
        EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << "wait status " << *status;
    }

    static size_t count(const std::vector<Datagram> &datagrams, const std::string &key)
    {
        return size_t(std::count_if(datagrams.begin(), datagrams.end(), [&](auto &d) { return d.has(key); }));
    }

    std::string binary_ = OVERLAYD_BINARY;
    test::TempDir dir_;
    test::NotifySocket socket_{dir_.path() / "notify"};
    std::unique_ptr<test::DaemonProcess> daemon_;
    std::vector<Datagram> history_;
};

TEST_F(DaemonNotifyTest, ReadyThenWatchdogWhileFramesFlowThenStopping)
{
    start(syntheticConfig(320, 0));
    ASSERT_TRUE(waitFor("READY", 20s)) << "no READY=1";
    auto flowing = collect(2s);
    EXPECT_GE(count(flowing, "WATCHDOG"), 3u) << "WATCHDOG_USEC=" << watchdogUsec << ": expected a pet every 200 ms";
    EXPECT_EQ(count(flowing, "READY"), 0u) << "READY=1 once per start, not per frame";
    stopCleanly();
}

TEST_F(DaemonNotifyTest, NoReadyBeforeTheFirstFrame)
{
    // A camera that is not there: the daemon keeps running and retrying, says so, and must not claim readiness.
    std::string config = syntheticConfig(320, 0);
    config.replace(config.find("kind = \"synthetic\""), 18, "kind = \"v4l2\"");
    config += "[source.v4l2]\ndevice = \"" + (dir_.path() / "no-such-video").string() + "\"\n";
    start(config);
    auto waiting = collect(3s);
    EXPECT_EQ(count(waiting, "READY"), 0u) << "READY=1 without a single frame";
    EXPECT_GE(count(waiting, "STATUS"), 1u) << "a STATUS line should say what the daemon waits for";
    EXPECT_GE(count(waiting, "EXTEND_TIMEOUT_USEC"), 1u)
        << "a camera late at boot must not run into the unit's start-up timeout";
    EXPECT_TRUE(daemon_->running()) << "a missing camera is retried, not fatal";
    stopCleanly();
}

TEST_F(DaemonNotifyTest, ReloadKeepsReadinessWithGoodAndBadConfig)
{
    start(syntheticConfig(320, 0));
    ASSERT_TRUE(waitFor("READY", 20s));

    for (bool good : {true, false}) {
        SCOPED_TRACE(good ? "good config" : "bad config");
        writeConfig(good ? syntheticConfig(640, 0) : "[source]\nkind = \"banana\"\nwidth = -3\n");
        uint64_t before = test::monotonicMicroseconds();
        daemon_->signal(SIGHUP);
        auto reloading = waitFor("RELOADING", 10s);
        ASSERT_TRUE(reloading) << "no RELOADING=1 after SIGHUP";
        auto fields = reloading->fields();
        ASSERT_TRUE(fields.count("MONOTONIC_USEC")) << reloading->text;
        uint64_t stamp = std::stoull(fields["MONOTONIC_USEC"]);
        EXPECT_GE(stamp, before) << "MONOTONIC_USEC must be CLOCK_MONOTONIC at the reload";
        EXPECT_LE(stamp, reloading->receivedUsec);

        size_t afterReloading = history_.size();
        ASSERT_TRUE(waitFor("READY", 20s)) << "no READY=1 after the reload";
        collect(300ms); // a STATUS may follow READY in its own datagram
        std::vector<Datagram> around(history_.begin() + afterReloading, history_.end());
        if (!good) {
            EXPECT_GE(count(around, "STATUS"), 1u) << "a rejected config must be reported in STATUS";
        }
        EXPECT_TRUE(waitFor("WATCHDOG", 5s)) << "frames should still flow after the reload";
    }
    EXPECT_TRUE(daemon_->running());
    stopCleanly();
}

// A reload that cannot be carried out whole (its replay file is missing, its sink is under a file) is refused:
// STATUS= says so and why, and the watchdog keeps being petted (frames flow from the old config).
TEST_F(DaemonNotifyTest, RefusedReloadSaysWhyInStatusWhileTheOldConfigStreams)
{
    start(syntheticConfig(320, 0));
    ASSERT_TRUE(waitFor("READY", 20s));
    writeConfig("[source]\nkind = \"replay\"\n[source.replay]\npath = \"" + (dir_.path() / "missing.y4m").string() +
                "\"\n[[sink]]\nkind = \"y4m\"\npath = \"" + (dir_.path() / "camera.toml" / "out.y4m").string() +
                "\"\n");
    daemon_->signal(SIGHUP);
    auto refused = waitFor("STATUS", 10s);
    while (refused && refused->fields()["STATUS"].find("reload refused") == std::string::npos)
        refused = waitFor("STATUS", 10s);
    ASSERT_TRUE(refused) << "no STATUS= saying the reload was refused";
    // The loader finds the missing replay file first (check-config would refuse it too), before any source is
    // opened, and counts the sink's path among the rest.
    EXPECT_NE(refused->fields()["STATUS"].find("source.replay.path"), std::string::npos) << refused->text;
    EXPECT_NE(refused->fields()["STATUS"].find("missing.y4m: does not exist"), std::string::npos) << refused->text;
    EXPECT_NE(refused->fields()["STATUS"].find("(and 1 more problems)"), std::string::npos) << refused->text;
    EXPECT_TRUE(waitFor("READY", 10s)) << "no READY=1 after the refused reload";
    auto flowing = collect(1s);
    EXPECT_GE(count(flowing, "WATCHDOG"), 2u) << "frames should still flow from the old config";
    EXPECT_TRUE(daemon_->running());
    stopCleanly();
}

TEST_F(DaemonNotifyTest, WatchdogStopsWhenThePipelineStalls)
{
    start(syntheticConfig(320, 30)); // about one second of frames, then a wedged source
    ASSERT_TRUE(waitFor("READY", 20s));
    // No fixed deadline for the stall (a loaded machine delivers the 30 frames late): wait for 1.5 s without a pet
    // (about 4 intervals), then demand that the silence lasts. A daemon that keeps petting never gets there.
    uint64_t lastPet = history_.back().receivedUsec;
    size_t pets = 0;
    bool quiet = false;
    for (auto end = std::chrono::steady_clock::now() + 10s; !quiet && std::chrono::steady_clock::now() < end;) {
        if (auto d = socket_.receive(100ms)) {
            record(*d);
            if (d->has("WATCHDOG")) {
                lastPet = d->receivedUsec;
                ++pets;
            }
        }
        quiet = test::monotonicMicroseconds() > lastPet + 1500000;
    }
    EXPECT_GE(pets, 1u) << "no WATCHDOG=1 while the first 30 frames flowed";
    ASSERT_TRUE(quiet) << "still petting the watchdog 10 s after READY, with a source that stalls after 30 frames";
    EXPECT_EQ(count(collect(2s), "WATCHDOG"), 0u) << "the watchdog was petted again with the source still stalled";
    EXPECT_TRUE(daemon_->running()) << "the daemon stays up; it is systemd's watchdog that restarts it";
    bool statusSaysStalled = false;
    for (const auto &d : history_) {
        const auto fields = d.fields();
        if (auto it = fields.find("STATUS"); it != fields.end() && it->second.find("stalled") != std::string::npos)
            statusSaysStalled = true;
    }
    EXPECT_TRUE(statusSaysStalled) << "STATUS= still claims streaming while no frame arrives";
    stopCleanly();
}

TEST_F(DaemonNotifyTest, RunByHandSendsNothingAndExitsCleanly)
{
    start(syntheticConfig(320, 0), /*withSocket=*/false);
    auto heard = collect(1500ms);
    EXPECT_TRUE(heard.empty());
    EXPECT_TRUE(daemon_->running());
    daemon_->signal(SIGTERM);
    auto status = daemon_->wait(15s);
    ASSERT_TRUE(status);
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << "wait status " << *status;
}

} // namespace
} // namespace overlayd
