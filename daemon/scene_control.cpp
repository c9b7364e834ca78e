// SceneControl: validation of each change with the config's own code (CameraSpec::build composes the camera exactly
// as loading [camera] does), and its application to the live renderer.
#include "daemon/scene_control.h"

#include <algorithm>

namespace overlayd {

void SceneControl::load(const OverlayScene &scene, const CameraSpec &camera)
{
    scene_ = scene;
    camera_ = camera;
}

Result<std::unique_ptr<OverlayRenderer>> SceneControl::build(const StreamFormat &format) const
{
    return buildFor(scene_, camera_, format);
}

Result<std::unique_ptr<OverlayRenderer>> SceneControl::buildFor(const OverlayScene &scene, const CameraSpec &camera,
                                                                const StreamFormat &format) const
{
    auto built = camera.build(format.width, format.height);
    if (!built)
        return makeError(built.error().code, "overlay: camera: " + built.error().message);
    auto renderer = factory_(scene, *built, format);
    if (!renderer)
        return makeError(renderer.error().code, "overlay: " + renderer.error().message);
    if (*renderer)
        for (const auto &[layer, visible] : layerVisible_)
            (void)(*renderer)->setLayerEnabled(layer, visible); // a layer the new scene lacks has nothing to hide
    return renderer;
}

void SceneControl::attach(OverlayRenderer *renderer, const StreamFormat &format)
{
    renderer_ = renderer;
    format_ = format;
}

Status SceneControl::apply(const SceneChange &change, std::unique_ptr<OverlayRenderer> *replaced)
{
    if (const auto *camera = std::get_if<CameraChange>(&change))
        return applyCamera(*camera);
    if (const auto *layer = std::get_if<LayerChange>(&change))
        return applyLayer(*layer);
    return applyScene(std::get<SceneReplacement>(change), replaced);
}

Status SceneControl::applyCamera(const CameraChange &change)
{
    if (!format_.format)
        return makeError(ErrorCode::TryAgain, "camera: no stream is open yet");
    auto camera = change.camera.build(format_.width, format_.height);
    if (!camera)
        return makeError(camera.error().code, "camera: " + camera.error().message);
    if (renderer_)
        if (auto set = renderer_->setCamera(*camera); !set)
            return makeError(set.error().code, "camera: " + set.error().message);
    camera_ = change.camera;
    return Ok{};
}

Status SceneControl::applyLayer(const LayerChange &change)
{
    const std::vector<std::string> names = layerNames();
    if (std::find(names.begin(), names.end(), change.layer) == names.end()) {
        std::string known;
        for (const std::string &name : names)
            known += (known.empty() ? "" : ", ") + name;
        return makeError(ErrorCode::InvalidArgument, "unknown layer '" + change.layer +
                                                         "' (the scene has: " + (known.empty() ? "none" : known) + ")");
    }
    if (renderer_)
        if (auto set = renderer_->setLayerEnabled(change.layer, change.visible); !set)
            return set;
    layerVisible_[change.layer] = change.visible;
    return Ok{};
}

Status SceneControl::applyScene(const SceneReplacement &change, std::unique_ptr<OverlayRenderer> *replaced)
{
    if (format_.format) {
        auto renderer = buildFor(change.scene, change.camera, format_);
        if (!renderer)
            return renderer.error();
        if (replaced)
            *replaced = std::move(*renderer);
    }
    scene_ = change.scene;
    camera_ = change.camera;
    return Ok{};
}

std::vector<std::string> SceneControl::layerNames() const
{
    std::vector<std::string> names;
    for (const Annotation &annotation : scene_.annotations)
        if (std::find(names.begin(), names.end(), annotation.style.layer) == names.end())
            names.push_back(annotation.style.layer);
    return names;
}

bool SceneControl::layerVisible(const std::string &layer) const
{
    const auto found = layerVisible_.find(layer);
    return found == layerVisible_.end() || found->second;
}

} // namespace overlayd
