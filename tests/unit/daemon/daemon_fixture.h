// SPDX-License-Identifier: Apache-2.0
// The daemon's unit-test fixture: a Daemon over a fake source, recording sinks keyed by path and a renderer that
// marks frames, loading whatever `file` says the config file holds now.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daemon/daemon.h"
#include "fakes.h"

namespace overlayd::test {

struct DaemonTest : ::testing::Test {
    std::vector<std::string> logLines;
    Logger logger{[this](std::string_view line) { logLines.emplace_back(line); }, true};
    test::RecordingNotifier notifier;
    std::shared_ptr<FakeSource::Shared> source = std::make_shared<FakeSource::Shared>();
    std::map<std::string, std::shared_ptr<RecordingSink::Shared>> sinks;
    bool rendererFails = false;
    // What the config file says now: a config, or problems.
    std::optional<DaemonConfig> file = makeConfig(1, "a");
    std::vector<ConfigProblem> fileProblems;

    // `mark` is the number of annotations: MarkingRenderer writes it into each frame it blends.
    static DaemonConfig makeConfig(size_t mark, const std::string &sinkPath)
    {
        DaemonConfig config;
        config.path = "test.toml";
        config.source.kind = SourceKind::Synthetic;
        config.source.synthetic.pattern = SyntheticPattern::ColourBars;
        config.source.pixelFormat = pixelFormatFromName("GREY");
        config.source.width = 64;
        config.source.height = 48;
        config.scene.annotations.resize(mark, Annotation{"a", "world", {}, AxesShape{}});
        SinkOptions sink;
        sink.kind = SinkKind::Null;
        sink.path = sinkPath;
        config.sinks.push_back(sink);
        config.daemon.statsIntervalSec = 0;
        return config;
    }

    StageFactories factories()
    {
        StageFactories f;
        f.source = [this](const SourceOptions &options, const Camera *) -> Result<std::unique_ptr<FrameSource>> {
            return std::unique_ptr<FrameSource>(
                std::make_unique<FakeSource>(source, test::greyFormat(options.width, options.height)));
        };
        f.sink = [this](const SinkOptions &options) -> Result<std::unique_ptr<FrameSink>> {
            auto &shared = sinks[options.path];
            if (!shared)
                shared = std::make_shared<RecordingSink::Shared>();
            return std::unique_ptr<FrameSink>(std::make_unique<RecordingSink>(shared, options.path));
        };
        f.renderer = [this](const OverlayScene &scene, const Camera &,
                            const StreamFormat &) -> Result<std::unique_ptr<OverlayRenderer>> {
            if (rendererFails)
                return makeError(ErrorCode::InvalidArgument, "annotation 'a': unknown frame 'base'");
            return std::unique_ptr<OverlayRenderer>(
                std::make_unique<test::MarkingRenderer>(uint8_t(scene.annotations.size())));
        };
        return f;
    }

    std::unique_ptr<Daemon> makeDaemon(uint64_t maxFrames = 0)
    {
        ConfigLoader loader = [this](const std::string &,
                                     std::vector<ConfigProblem> &problems) -> Result<DaemonConfig> {
            if (file)
                return *file;
            problems = fileProblems;
            return makeError(ErrorCode::ConfigError, "invalid");
        };
        return std::make_unique<Daemon>(logger, notifier, factories(), loader,
                                        DaemonOptions{"test.toml", std::nullopt, maxFrames});
    }

    bool logged(const std::string &text) const
    {
        for (const std::string &line : logLines)
            if (line.find(text) != std::string::npos)
                return true;
        return false;
    }
};

} // namespace overlayd::test
