// Pipeline during a reload: the new sinks open before the running ones close, except where both write to one place.
#include "daemon/pipeline.h"

#include <algorithm>

namespace overlayd {

namespace {

// Two sinks that write to one place (a file, a device, stdout, the HTTP feed) cannot both be open: the new one waits
// until the running one has closed.
bool sameOutput(const SinkWorker &a, const SinkWorker &b)
{
    return !a.options().path.empty() && a.options().path == b.options().path;
}

Status openFor(SinkWorker &sink, const StreamFormat &format)
{
    if (auto opened = sink.open(format); !opened)
        return makeError(opened.error().code,
                         cat(sink.describe(), ": cannot open for ", format.describe(), ": ", opened.error().message));
    return Ok{};
}

} // namespace

Status Pipeline::replaceSinks(std::vector<std::unique_ptr<SinkWorker>> sinks, const StreamFormat &format)
{
    const auto takesOver = [this](const SinkWorker &sink) {
        return std::any_of(sinks_.begin(), sinks_.end(),
                           [&](const auto &running) { return sameOutput(*running, sink); });
    };
    // First the sinks that write elsewhere, while the running ones still write; then, once those have written what
    // they hold and closed, the ones that take over their files and devices.
    for (const bool afterRunning : {false, true}) {
        if (afterRunning)
            closeSinks();
        for (auto &sink : sinks) {
            if (takesOver(*sink) != afterRunning)
                continue;
            if (auto opened = openFor(*sink, format); !opened) {
                for (auto &each : sinks)
                    (void)each->close();
                if (afterRunning)
                    restoreSinks();
                return opened;
            }
        }
    }
    setSinks(std::move(sinks));
    format_ = format;
    return Ok{};
}

Status Pipeline::reopenSinks(const StreamFormat &format)
{
    for (auto &sink : sinks_)
        if (auto opened = openFor(*sink, format); !opened) {
            restoreSinks();
            return opened;
        }
    format_ = format;
    return Ok{};
}

void Pipeline::restoreSinks()
{
    for (auto &sink : sinks_)
        if (auto opened = openFor(*sink, format_); !opened)
            logger_.error(opened.error().message);
}

} // namespace overlayd
