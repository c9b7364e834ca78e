// SPDX-License-Identifier: Apache-2.0
// HealthReporter: the readiness, watchdog and STATUS= rules, and the stats line.
#include "daemon/health_reporter.h"

#include "base/number_text.h"
#include <cstdio>

namespace overlayd {

void HealthReporter::frameDelivered(const StreamFormat &format)
{
    ++framesSincePet_;
    if (readySent_)
        return;
    readySent_ = true;
    notifier_.ready();
    streaming(format);
}

void HealthReporter::streaming(const StreamFormat &format)
{
    notifier_.status(cat("streaming ", format.describe(), ", ", totalDrops_, " drops",
                         refusedReload_.empty() ? "" : "; last reload refused: ", refusedReload_));
}

void HealthReporter::reloadRefused(const std::string &why)
{
    refusedReload_ = why;
    notifier_.status(cat("reload refused, kept the previous config: ", why));
}

void HealthReporter::onStats(Pipeline &pipeline, bool streaming)
{
    const PipelineStats stats = pipeline.takeStats();
    totalDrops_ = stats.totalDrops;
    logger_.info(cat("stats: ", stats.describe()));
    if (streaming)
        this->streaming(pipeline.format());
}

void HealthReporter::onWatchdog(bool streaming, bool reconnecting, const StreamFormat &format,
                                const std::string &source)
{
    if (framesSincePet_ > 0 || reconnecting)
        notifier_.watchdog();
    const bool stalled = streaming && framesSincePet_ == 0;
    framesSincePet_ = 0;
    if (!stalled) {
        if (idleWatchdogTicks_ > 0 && streaming)
            this->streaming(format);
        idleWatchdogTicks_ = 0;
        return;
    }
    // A stalled stream stops the watchdog; STATUS= says why, so `systemctl status` does not keep claiming
    // "streaming".
    ++idleWatchdogTicks_;
    const auto interval = notifier_.watchdogInterval().value_or(std::chrono::microseconds(0));
    const double idleSec = double(idleWatchdogTicks_) * double(interval.count()) * 1e-6;
    notifier_.status(formatted("stalled: no frame from %s for %.1f s", source.c_str(), idleSec));
}

} // namespace overlayd
