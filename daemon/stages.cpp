// StageFactories: the production wiring, and option comparison for reloads.
#include "daemon/stages.h"

#include <tuple>

#include "drivers/sink_options.h"
#include "drivers/source_options.h"

namespace overlayd {

namespace {

Result<std::unique_ptr<FrameSource>> buildSource(const DaemonConfig &config)
{
    SourceOptions options = config.source;
    options.v4l2.exportDmabuf = wantsZeroCopy(config);
    if (options.kind == SourceKind::Synthetic && options.synthetic.pattern == SyntheticPattern::CheckerboardScene) {
        // The scene is ray-traced through the same camera the overlay uses, so that the two can be compared.
        auto camera = config.camera.build(options.width, options.height);
        if (!camera)
            return makeError(camera.error().code, "camera: " + camera.error().message);
        options.synthetic.camera = std::move(*camera);
    }
    return makeSource(options);
}

Result<std::unique_ptr<OverlayRenderer>> buildRenderer(const OverlayScene &scene, const Camera &camera,
                                                       const StreamFormat &format)
{
    if (scene.annotations.empty())
        return std::unique_ptr<OverlayRenderer>();
    return OverlayRenderer::create(scene, camera, format);
}

// The fields a source is built from (the synthetic camera is compared separately: it comes from [camera]).
auto sourceKey(const SourceOptions &o)
{
    const SyntheticOptions &s = o.synthetic;
    const ReplayOptions &r = o.replay;
    const V4l2CaptureOptions &v = o.v4l2;
    return std::tuple(o.kind, o.pixelFormat, o.width, o.height, o.fps, o.colorimetry, s.pattern, s.seed, s.checkerPx,
                      s.checkerMetres, s.stallAfterFrames, r.path, r.format, r.loop, r.firstIndex, v.device,
                      v.bufferCount, v.noSignalTimeoutSec);
}

auto sinkKey(const SinkOptions &o)
{
    return std::tuple(o.kind, o.path, o.every, o.jpegQuality, o.queueDepth, o.dropPolicy, o.bufferCount, o.zeroCopy);
}

bool drawsThroughCamera(const SourceOptions &o)
{
    return o.kind == SourceKind::Synthetic && o.synthetic.pattern == SyntheticPattern::CheckerboardScene;
}

// Two cameras that map every pixel the same way: same pose, projection, lens and viewport mapping.
bool sameMapping(const Camera &a, const Camera &b)
{
    const auto lensOf = [](const Camera &c) {
        return c.lens() ? std::pair(c.lens()->distortion().model, c.lens()->distortion().coeffs)
                        : std::pair(DistortionModel::None, std::array<double, 8>{});
    };
    const Viewport &va = a.viewport(), &vb = b.viewport();
    return a.view() == b.view() && a.projection().matrix() == b.projection().matrix() && lensOf(a) == lensOf(b) &&
           va.window() == vb.window() && va.ndcToPixel({1, 1}) == vb.ndcToPixel({1, 1}) &&
           va.ndcToPixel({-1, -1}) == vb.ndcToPixel({-1, -1});
}

} // namespace

bool wantsZeroCopy(const DaemonConfig &config)
{
    for (const SinkOptions &sink : config.sinks)
        if (sink.kind == SinkKind::V4l2Output && sink.zeroCopy != ZeroCopy::Off)
            return true;
    return false;
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

bool sceneCameraChanged(const DaemonConfig &a, const DaemonConfig &b)
{
    if (!drawsThroughCamera(b.source))
        return false;
    auto before = a.camera.build(a.source.width, a.source.height);
    auto after = b.camera.build(b.source.width, b.source.height);
    return !before || !after || !sameMapping(*before, *after);
}

StageFactories defaultStageFactories()
{
    return StageFactories{buildSource, [](const SinkOptions &options) { return makeSink(options); }, buildRenderer};
}

bool sameSourceOptions(const SourceOptions &a, const SourceOptions &b)
{
    return sourceKey(a) == sourceKey(b);
}

bool sameSinkOptions(const std::vector<SinkOptions> &a, const std::vector<SinkOptions> &b)
{
    if (a.size() != b.size())
        return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (sinkKey(a[i]) != sinkKey(b[i]))
            return false;
    return true;
}

} // namespace overlayd
