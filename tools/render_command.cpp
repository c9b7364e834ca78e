// SPDX-License-Identifier: Apache-2.0
// `overlayd render`: N frames of the configured source through the overlay into one output, unpaced, losing none.
#include "tools/commands.h"

#include <poll.h>
#include <thread>

#include "daemon/open_stream.h"
#include "daemon/pipeline.h"
#include "daemon/stages.h"

namespace overlayd {

namespace {

bool endsWith(const std::string &text, std::string_view suffix)
{
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A source with nothing ready: wait on its fd (a device) or briefly (a paced source that stalls on purpose).
void waitForFrame(const FrameSource &source)
{
    if (source.eventFd() >= 0) {
        pollfd fd{source.eventFd(), POLLIN, 0};
        ::poll(&fd, 1, 100);
    } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

// Pulls `frames` frames through the pipeline; EndOfStream ends early and cleanly.
Status pump(FrameSource &source, Pipeline &pipeline, uint64_t frames, Logger &logger)
{
    constexpr auto kStallLimit = std::chrono::seconds(5);
    auto lastFrame = std::chrono::steady_clock::now();
    while (pipeline.framesIn() < frames) {
        auto frame = source.nextFrame();
        if (frame) {
            pipeline.process(frame->view(), frame->metadata());
            lastFrame = std::chrono::steady_clock::now();
            continue;
        }
        if (frame.error().code == ErrorCode::EndOfStream) {
            logger.notice(cat("the source ended after ", pipeline.framesIn(), " of ", frames, " frames"));
            return Ok{};
        }
        if (frame.error().code != ErrorCode::TryAgain)
            return frame.error();
        if (std::chrono::steady_clock::now() - lastFrame > kStallLimit)
            return makeError(ErrorCode::DeviceLost,
                             cat("the source delivered no frame for 5 s after frame ", pipeline.framesIn()));
        waitForFrame(source);
    }
    return Ok{};
}

} // namespace

Result<SinkOptions> sinkForOutput(const std::string &path)
{
    SinkOptions sink;
    sink.path = path;
    sink.queueDepth = 4;
    if (endsWith(path, ".y4m")) {
        sink.kind = SinkKind::Y4m;
    } else if (endsWith(path, ".yuv") || endsWith(path, ".raw")) {
        sink.kind = SinkKind::Raw;
    } else if (path.find('%') != std::string::npos || endsWith(path, ".png") || endsWith(path, ".jpg") ||
               endsWith(path, ".jpeg")) {
        sink.kind = SinkKind::Snapshot;
        sink.every = 1;
    } else {
        return makeError(ErrorCode::InvalidArgument,
                         "cannot tell the output format from '" + path + "' (use .y4m, .yuv, .raw or %04d.png)");
    }
    return sink;
}

int renderCommand(const std::string &configPath, uint64_t frames, const std::string &output,
                  std::optional<LogLevel> logLevel, Logger &logger)
{
    auto sinkOptions = sinkForOutput(output);
    if (!sinkOptions) {
        logger.error(sinkOptions.error().message);
        return kExitFailure;
    }
    auto config = loadConfigLogged(configPath, logger);
    if (!config)
        return kExitConfigError;
    logger.setLevel(logLevel.value_or(config->daemon.logLevel));
    const StageFactories factories = defaultStageFactories();
    auto sink = factories.sink(*sinkOptions);
    if (!sink) {
        logger.error(sink.error().message);
        return kExitFailure;
    }
    Pipeline pipeline(logger);
    std::vector<std::unique_ptr<SinkWorker>> sinks;
    sinks.push_back(std::make_unique<SinkWorker>(std::move(*sink), *sinkOptions, logger, /*lossless=*/true));
    pipeline.setSinks(std::move(sinks));
    SceneControl scene(factories.renderer);
    scene.load(config->scene, config->camera);
    OpenFailure failure;
    auto source = openStream(factories.source, *config, scene, pipeline, /*sinksMustOpen=*/true, &failure);
    if (!source) {
        if (failure.step == OpenStep::BuildOverlay) {
            logger.error(cat(configPath, ": ", source.error().message));
            return kExitConfigError;
        }
        if (failure.step == OpenStep::StartSource)
            logger.error(cat(failure.source, ": ", source.error().message));
        else if (failure.step == OpenStep::CreateSource)
            logger.error(source.error().message);
        return kExitFailure; // a sink that cannot open has said why
    }
    const StreamFormat format = pipeline.format();
    logger.info(
        cat("rendering ", frames, " frames of ", (*source)->describe(), " (", format.describe(), ") to ", output));
    const auto start = std::chrono::steady_clock::now();
    const Status pumped = pump(**source, pipeline, frames, logger);
    (*source)->stop();
    pipeline.closeSinks();
    const PipelineStats stats = pipeline.takeStats();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!pumped) {
        logger.error(cat((*source)->describe(), ": ", pumped.error().message));
        return kExitFailure;
    }
    const uint64_t failed = stats.sinks.empty() ? 0 : stats.sinks[0].counters.failed;
    logger.info(cat("rendered ", pipeline.framesIn(), " frames in ", seconds, " s: ", stats.describe()));
    return failed ? kExitFailure : kExitOk;
}

} // namespace overlayd
