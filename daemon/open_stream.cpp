// SPDX-License-Identifier: Apache-2.0
// openStream: source, format, overlay, sinks, in that order, each failure leaving the running pipeline as it was.
#include "daemon/open_stream.h"

#include <optional>

namespace overlayd {

Result<OpenedStream> startStream(const SourceFactory &makeSource, const DaemonConfig &config, const SceneControl &scene,
                                 OpenFailure *failure)
{
    OpenFailure unused;
    OpenFailure &failed = failure ? *failure : unused;
    failed.step = OpenStep::CreateSource;
    SourceOptions options = config.source;
    options.v4l2.exportDmabuf = wantsZeroCopy(config);
    // The synthetic scene is ray-traced through the camera the overlay uses, so that the two can be compared; for
    // a source that produces its configured size, SceneControl builds that camera once for both.
    std::optional<Camera> sceneCamera;
    if (drawsThroughCamera(options)) {
        auto camera = scene.cameraFor(options.width, options.height);
        if (!camera)
            return makeError(camera.error().code, "camera: " + camera.error().message);
        sceneCamera.emplace(std::move(*camera));
    }
    auto source = makeSource(options, sceneCamera ? &*sceneCamera : nullptr);
    if (!source)
        return source.error();
    failed.source = (*source)->describe();
    auto format = (*source)->start();
    if (!format) {
        failed.step = OpenStep::StartSource;
        return format.error();
    }
    auto renderer = scene.build(*format);
    if (!renderer) {
        (*source)->stop();
        failed.step = OpenStep::BuildOverlay;
        return renderer.error();
    }
    return OpenedStream{std::move(*source), *format, std::move(*renderer)};
}

std::unique_ptr<FrameSource> runStream(OpenedStream stream, SceneControl &scene, Pipeline &pipeline)
{
    pipeline.setRenderer(std::move(stream.renderer));
    scene.attach(pipeline.renderer(), stream.format);
    return std::move(stream.source);
}

Result<std::unique_ptr<FrameSource>> openStream(const SourceFactory &makeSource, const DaemonConfig &config,
                                                SceneControl &scene, Pipeline &pipeline, bool sinksMustOpen,
                                                OpenFailure *failure)
{
    OpenFailure unused;
    OpenFailure &failed = failure ? *failure : unused;
    auto stream = startStream(makeSource, config, scene, &failed);
    if (!stream)
        return stream.error();
    if (pipeline.format() != stream->format)
        if (auto opened = pipeline.openSinks(stream->format); !opened && sinksMustOpen) {
            stream->source->stop();
            failed.step = OpenStep::OpenSinks;
            return opened.error();
        }
    return runStream(std::move(*stream), scene, pipeline);
}

} // namespace overlayd
