// openStream: source, format, overlay, sinks, in that order, each failure leaving the running pipeline as it was.
#include "daemon/open_stream.h"

namespace overlayd {

Result<std::unique_ptr<FrameSource>> openStream(const SourceFactory &makeSource, const DaemonConfig &config,
                                                SceneControl &scene, Pipeline &pipeline, bool sinksMustOpen,
                                                OpenFailure *failure)
{
    OpenFailure unused;
    OpenFailure &failed = failure ? *failure : unused;
    auto source = makeSource(config);
    if (!source) {
        failed.step = OpenStep::CreateSource;
        return source.error();
    }
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
    const StreamFormat &current = pipeline.format();
    const bool formatChanged = current.format != format->format || current.width != format->width ||
                               current.height != format->height || current.stride != format->stride ||
                               !(current.colorimetry == format->colorimetry) || current.fps != format->fps ||
                               current.dmabufBuffers != format->dmabufBuffers;
    if (formatChanged)
        if (auto opened = pipeline.openSinks(*format); !opened && sinksMustOpen) {
            (*source)->stop();
            failed.step = OpenStep::OpenSinks;
            return opened.error();
        }
    pipeline.setRenderer(std::move(*renderer));
    scene.attach(pipeline.renderer(), *format);
    return std::move(*source);
}

} // namespace overlayd
