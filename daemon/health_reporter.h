// SPDX-License-Identifier: Apache-2.0
// HealthReporter: what systemd and the log hear about the stream: READY=1 once the first frame is through, a
// watchdog petted only while frames flow (or a reconnect runs), STATUS= lines, and the periodic stats line.
#pragma once

#include <cstdint>
#include <string>

#include "base/logger.h"
#include "daemon/pipeline.h"
#include "daemon/systemd_notify.h"

namespace overlayd {

class HealthReporter
{
public:
    HealthReporter(Logger &logger, SystemdNotifier &notifier) : logger_(logger), notifier_(notifier) {}

    SystemdNotifier &notifier() { return notifier_; }
    bool readySent() const { return readySent_; }

    // A source frame went through the pipeline: the watchdog may be petted; the first one makes the unit ready.
    void frameDelivered(const StreamFormat &format);
    // STATUS= for a stream that flows: its format and the drops counted at the last stats line.
    void streaming(const StreamFormat &format);
    // STATUS= while the source is down.
    void waiting(const std::string &line) { notifier_.status(line); }
    // STATUS= after a refused reload says why; while the old config streams on, each "streaming" line repeats it
    // (`systemctl status` must not hide that the file on disk is not what runs) until a reload is accepted.
    void reloadRefused(const std::string &why);
    void reloadAccepted() { refusedReload_.clear(); }

    // The periodic stats line (also refreshes STATUS= while streaming).
    void onStats(Pipeline &pipeline, bool streaming);
    // A watchdog tick: pet only when frames flowed since the last one, or while a deliberate reconnect runs (the
    // NO SIGNAL frames prove the loop itself is alive); a stalled stream says so in STATUS=.
    void onWatchdog(bool streaming, bool reconnecting, const StreamFormat &format, const std::string &source);

private:
    Logger &logger_;
    SystemdNotifier &notifier_;
    uint64_t framesSincePet_ = 0;
    unsigned idleWatchdogTicks_ = 0; // watchdog ticks in a row without a frame while streaming (for STATUS=)
    bool readySent_ = false;
    uint64_t totalDrops_ = 0;
    std::string refusedReload_; // why the last reload was refused, until one is accepted
};

} // namespace overlayd
