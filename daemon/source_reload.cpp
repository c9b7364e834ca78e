// SourceSupervisor during a reload that changes the source: the new stream is opened before anything is switched,
// beside the running one or, for the same device, in its place with the way back kept open.
#include "daemon/source_supervisor.h"

namespace overlayd {

Result<SourceSupervisor::Staged> SourceSupervisor::stage(const DaemonConfig &next, const SceneControl &nextScene)
{
    Staged staged;
    staged.closedRunning = source_ && mayShareDevice(config_.source, next.source);
    if (staged.closedRunning)
        close();
    OpenFailure failure;
    auto stream = startStream(makeSource_, next, nextScene, &failure);
    if (stream) {
        staged.stream = std::move(*stream);
        return staged;
    }
    std::string why = stream.error().message;
    if (failure.step == OpenStep::StartSource && why.find(failure.source) == std::string::npos)
        why = cat(failure.source, ": ", why);
    if (staged.closedRunning)
        if (auto back = reopenRunning(); !back)
            why += cat("; the running source did not open again either: ", back.error().message);
    return makeError(stream.error().code, why);
}

void SourceSupervisor::adopt(Staged staged)
{
    close();
    startStreaming(runStream(std::move(staged.stream), scene_, pipeline_));
}

void SourceSupervisor::discard(Staged staged)
{
    if (staged.stream.source)
        staged.stream.source->stop();
    staged.stream = {};
    if (staged.closedRunning)
        (void)reopenRunning();
}

Status SourceSupervisor::reopenRunning()
{
    auto opened = open();
    if (!opened)
        enterWaiting(opened.error());
    return opened;
}

} // namespace overlayd
