// SPDX-License-Identifier: Apache-2.0
// OverlayRenderer::create: validates the scene, the camera and the stream format, then renders once.
#include "overlay/overlay_renderer.h"

#include "overlay/scene_renderer.h"
#include "overlay/shapes/scene_checks.h"

namespace overlayd {

Result<std::unique_ptr<OverlayRenderer>> OverlayRenderer::create(const OverlayScene &scene, const Camera &camera,
                                                                 const StreamFormat &format)
{
    if (!format.format || format.width == 0 || format.height == 0 || format.width > kMaxFrameDimension ||
        format.height > kMaxFrameDimension)
        return makeError(ErrorCode::InvalidArgument, "overlay needs a stream format with a pixel format and a size");
    if (camera.viewport().frameWidth() != int(format.width) || camera.viewport().frameHeight() != int(format.height))
        return makeError(ErrorCode::InvalidArgument,
                         "the camera's viewport is " + std::to_string(camera.viewport().frameWidth()) + "x" +
                             std::to_string(camera.viewport().frameHeight()) + ", the stream " +
                             std::to_string(format.width) + "x" + std::to_string(format.height));
    Result<SceneGraph> graph = scene.graph ? Result<SceneGraph>(*scene.graph) : SceneGraph::create(scene.frames);
    if (!graph)
        return graph.error();
    if (Status status = checkScene(scene, *graph); !status)
        return status.error();
    auto renderer = std::make_unique<SceneRenderer>(scene, std::move(*graph), camera, format);
    if (Status status = renderer->renderMasks(); !status)
        return status.error();
    if (Status status = renderer->renderWorld(); !status)
        return status.error();
    return std::unique_ptr<OverlayRenderer>(std::move(renderer));
}

} // namespace overlayd
