// SPDX-License-Identifier: Apache-2.0
// SystemdNotifier: tells systemd the truth about the daemon's health (sd_notify readiness, status, watchdog).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string_view>

namespace overlayd {

// The base class is the no-op notifier: what runs by hand (no NOTIFY_SOCKET) and what a build without libsystemd
// (OVERLAYD_SYSTEMD=OFF) gets. fromEnvironment() picks the real one only when there is someone to talk to, so the
// daemon calls these unconditionally and nothing is sent or fails when run outside systemd.
class SystemdNotifier
{
public:
    // The libsystemd notifier when NOTIFY_SOCKET is set and support is compiled in; otherwise a no-op notifier.
    static std::unique_ptr<SystemdNotifier> fromEnvironment();

    SystemdNotifier() = default;
    SystemdNotifier(const SystemdNotifier &) = delete;
    SystemdNotifier &operator=(const SystemdNotifier &) = delete;
    virtual ~SystemdNotifier();

    // READY=1: send once the first frame has gone through the pipeline, and again after each reload.
    virtual void ready() {}
    // RELOADING=1 with MONOTONIC_USEC= (CLOCK_MONOTONIC now), as systemd >= 253 requires for Type=notify-reload.
    virtual void reloading() {}
    // STOPPING=1: shutdown has begun.
    virtual void stopping() {}
    // STATUS=<line>: one human-readable line for `systemctl status`; line breaks are folded into spaces.
    virtual void status(std::string_view line) { (void)line; }
    // WATCHDOG=1: only while frames flow (or a deliberate reconnect is in progress).
    virtual void watchdog() {}
    // EXTEND_TIMEOUT_USEC=: asks systemd for more start-up (or stop) time, e.g. while waiting for a camera to
    // appear before the first frame lets us send READY.
    virtual void extendTimeout(std::chrono::microseconds extra) { (void)extra; }

    // How often to call watchdog(): half of WATCHDOG_USEC, or nothing when systemd has no watchdog for us.
    virtual std::optional<std::chrono::microseconds> watchdogInterval() const { return std::nullopt; }
    // True when messages actually go somewhere (for log lines and tests).
    virtual bool active() const { return false; }
};

} // namespace overlayd
