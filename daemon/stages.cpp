// SPDX-License-Identifier: Apache-2.0
// StageFactories: the production wiring, and what a reload must re-open.
#include "daemon/stages.h"

#include <algorithm>
#include <filesystem>

#include "drivers/sink_options.h"
#include "drivers/source_options.h"
#include "overlay/scene_renderer.h"
#include "stream/engine_loader.h"

namespace overlayd {

namespace {

Result<std::unique_ptr<OverlayRenderer>> buildRenderer(const OverlayScene &scene, const Camera &camera,
                                                       const StreamFormat &format)
{
    if (scene.annotations.empty())
        return std::unique_ptr<OverlayRenderer>();
    return SceneRenderer::create(scene, camera, format);
}

} // namespace

bool drawsThroughCamera(const SourceOptions &options)
{
    return options.kind == SourceKind::Synthetic && options.synthetic.pattern == SyntheticPattern::CheckerboardScene;
}

bool wantsZeroCopy(const DaemonConfig &config)
{
    for (const SinkOptions &sink : config.sinks)
        if (sink.kind == SinkKind::V4l2Output && sink.zeroCopy != ZeroCopy::Off)
            return true;
    // A V4L2 encoder may import them as well ([encoder] zero_copy); a software encoder only ever gets copies.
    const EncoderOptions &encoder = config.stream.encoder;
    return config.stream.enabled() && encoder.zeroCopy != EncoderZeroCopy::Off &&
           (encoder.kind == EncoderKind::V4l2 || encoder.kind == EncoderKind::Auto);
}

Status limitZeroCopy(std::vector<SinkOptions> &sinks, std::vector<std::string> &notices)
{
    const auto wants = [](const SinkOptions &s, ZeroCopy mode) {
        return s.kind == SinkKind::V4l2Output && s.zeroCopy == mode;
    };
    const SinkOptions *keeper = nullptr;
    for (const SinkOptions &sink : sinks) {
        if (wants(sink, ZeroCopy::On) && keeper)
            return makeError(ErrorCode::ConfigError, "sinks " + keeper->path + " and " + sink.path +
                                                         " both have zero_copy = \"on\"; only one sink can hold the "
                                                         "camera's buffers");
        if (wants(sink, ZeroCopy::On))
            keeper = &sink;
    }
    for (SinkOptions &sink : sinks) {
        if (!wants(sink, ZeroCopy::Auto))
            continue;
        if (!keeper) {
            keeper = &sink;
            continue;
        }
        sink.zeroCopy = ZeroCopy::Off;
        notices.push_back("sink " + sink.path + ": copying (zero_copy \"auto\"): " + keeper->path +
                          " already takes the camera's buffers");
    }
    return Ok{};
}

Status limitEncoderZeroCopy(const std::vector<SinkOptions> &sinks, EncoderOptions &encoder,
                            std::vector<std::string> &notices)
{
    const auto keeper = std::find_if(sinks.begin(), sinks.end(), [](const SinkOptions &s) {
        return s.kind == SinkKind::V4l2Output && s.zeroCopy != ZeroCopy::Off;
    });
    if (keeper == sinks.end() || encoder.zeroCopy == EncoderZeroCopy::Off)
        return Ok{};
    if (encoder.zeroCopy == EncoderZeroCopy::On)
        return makeError(ErrorCode::ConfigError,
                         "[encoder] zero_copy = \"on\" and sink " + keeper->path +
                             " (zero_copy not \"off\"): only one can hold the camera's buffers");
    encoder.zeroCopy = EncoderZeroCopy::Off;
    notices.push_back("encoder: copying (zero_copy \"auto\"): " + keeper->path + " already takes the camera's buffers");
    return Ok{};
}

bool sceneCameraChanged(const DaemonConfig &a, const DaemonConfig &b)
{
    return drawsThroughCamera(b.source) && a.camera != b.camera;
}

bool mayShareDevice(const SourceOptions &running, const SourceOptions &next)
{
    if (running.kind != next.kind)
        return false;
    if (running.kind == SourceKind::Libcamera)
        return true;
    if (running.kind != SourceKind::V4l2)
        return false;
    std::error_code error;
    const auto a = std::filesystem::canonical(running.v4l2.device, error);
    if (error)
        return true;
    const auto b = std::filesystem::canonical(next.v4l2.device, error);
    return error || a == b;
}

StageFactories defaultStageFactories()
{
    return StageFactories{
        [](const SourceOptions &options, const Camera *sceneCamera) { return makeSource(options, sceneCamera); },
        [](const SinkOptions &options) { return makeSink(options); }, buildRenderer, makeLineProvider,
        loadStreamEngine};
}

} // namespace overlayd
