// SPDX-License-Identifier: Apache-2.0
// SystemdNotifier's libsystemd implementation; the only file that knows whether libsystemd was compiled in.
#include "daemon/systemd_notify.h"

#include <cstdlib>
#include <ctime>
#include <string>

#if OVERLAYD_HAVE_LIBSYSTEMD
#include <systemd/sd-daemon.h>
#endif

namespace overlayd {

SystemdNotifier::~SystemdNotifier() = default;

#if OVERLAYD_HAVE_LIBSYSTEMD

namespace {

uint64_t monotonicMicroseconds()
{
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return uint64_t(now.tv_sec) * 1000000u + uint64_t(now.tv_nsec) / 1000u;
}

// sd_notify() sends one datagram per call, so a state and its companions (RELOADING + MONOTONIC_USEC) go together.
// Failures are ignored on purpose: a lost notification must never take the frame path down, and systemd's own
// timeouts (start, watchdog) already catch a notifier that cannot reach it.
class SdNotifier final : public SystemdNotifier
{
public:
    SdNotifier()
    {
        uint64_t usec = 0;
        // 0: do not unset the environment; WATCHDOG_PID (when set) must be ours, which libsystemd checks.
        if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0)
            watchdogInterval_ = std::chrono::microseconds(usec / 2);
    }

    void ready() override { send("READY=1"); }
    void reloading() override { send("RELOADING=1\nMONOTONIC_USEC=" + std::to_string(monotonicMicroseconds())); }
    void stopping() override { send("STOPPING=1"); }
    void watchdog() override { send("WATCHDOG=1"); }

    void status(std::string_view line) override
    {
        std::string message = "STATUS=";
        for (char c : line)
            message += (c == '\n' || c == '\r') ? ' ' : c;
        send(message);
    }

    void extendTimeout(std::chrono::microseconds extra) override
    {
        send("EXTEND_TIMEOUT_USEC=" + std::to_string(extra.count() > 0 ? extra.count() : 0));
    }

    std::optional<std::chrono::microseconds> watchdogInterval() const override { return watchdogInterval_; }
    bool active() const override { return true; }

private:
    static void send(const std::string &message) { (void)sd_notify(0, message.c_str()); }

    std::optional<std::chrono::microseconds> watchdogInterval_;
};

} // namespace

std::unique_ptr<SystemdNotifier> SystemdNotifier::fromEnvironment()
{
    const char *socket = std::getenv("NOTIFY_SOCKET");
    if (socket == nullptr || *socket == '\0')
        return std::make_unique<SystemdNotifier>();
    return std::make_unique<SdNotifier>();
}

#else // libsystemd compiled out: always the no-op notifier.

std::unique_ptr<SystemdNotifier> SystemdNotifier::fromEnvironment()
{
    return std::make_unique<SystemdNotifier>();
}

#endif

} // namespace overlayd
