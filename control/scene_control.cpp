// SPDX-License-Identifier: Apache-2.0
// SceneControl: validation of each change with the config's own code (CameraSpec::build composes the camera exactly
// as loading [camera] does), and its application to the live renderer.
#include "control/scene_control.h"

#include <algorithm>
#include <cmath>

#include "overlay/shapes/scene_checks.h"

namespace overlayd {

void SceneControl::load(const OverlayScene &scene, const CameraSpec &camera)
{
    scene_ = scene;
    camera_ = camera;
    built_.reset();
}

Result<Camera> SceneControl::cameraFor(unsigned width, unsigned height) const
{
    if (built_ && builtWidth_ == width && builtHeight_ == height)
        return *built_;
    auto camera = camera_.build(width, height);
    if (camera) {
        built_ = *camera;
        builtWidth_ = width, builtHeight_ = height;
    }
    return camera;
}

Result<std::unique_ptr<OverlayRenderer>> SceneControl::build(const StreamFormat &format) const
{
    auto camera = cameraFor(format.width, format.height);
    if (!camera)
        return makeError(camera.error().code, "overlay: camera: " + camera.error().message);
    return buildFor(scene_, *camera, format);
}

Result<std::unique_ptr<OverlayRenderer>> SceneControl::buildFor(const OverlayScene &scene, const Camera &camera,
                                                                const StreamFormat &format) const
{
    auto renderer = factory_(scene, camera, format);
    if (!renderer)
        return makeError(renderer.error().code, "overlay: " + renderer.error().message);
    if (*renderer) {
        // A layer or slot the new scene lacks has nothing to hide or show.
        for (const auto &[layer, visible] : layerVisible_)
            (void)(*renderer)->setLayerEnabled(layer, visible);
        for (const auto &[slot, text] : slotTexts_)
            (void)(*renderer)->setSlotText(slot, text);
    }
    return renderer;
}

void SceneControl::attach(OverlayRenderer *renderer, const StreamFormat &format)
{
    renderer_ = renderer;
    format_ = format;
}

Status SceneControl::apply(const SceneChange &change)
{
    if (const auto *camera = std::get_if<CameraChange>(&change))
        return applyCamera(*camera);
    if (const auto *layer = std::get_if<LayerChange>(&change))
        return applyLayer(*layer);
    if (const auto *text = std::get_if<TextChange>(&change))
        return applyText(*text);
    if (const auto *steering = std::get_if<SteeringChange>(&change))
        return applySteering(*steering);
    return applyPoints(std::get<PointsChange>(change));
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
    built_ = std::move(*camera);
    builtWidth_ = format_.width, builtHeight_ = format_.height;
    return Ok{};
}

namespace {

// "unknown layer 'x' (the scene has: a, b)": a refusal that says what would have been accepted.
Status requireKnown(const char *what, const std::string &name, const std::vector<std::string> &known)
{
    if (std::find(known.begin(), known.end(), name) != known.end())
        return Ok{};
    std::string list;
    for (const std::string &each : known)
        list += (list.empty() ? "" : ", ") + each;
    return makeError(ErrorCode::InvalidArgument, std::string("unknown ") + what + " '" + name +
                                                     "' (the scene has: " + (list.empty() ? "none" : list) + ")");
}

} // namespace

Status SceneControl::applyLayer(const LayerChange &change)
{
    if (Status known = requireKnown("layer", change.layer, layerNames()); !known)
        return known;
    for (const Annotation &annotation : scene_.annotations)
        if (!change.visible && isMask(annotation) && annotation.style.layer == change.layer)
            return makeError(ErrorCode::InvalidArgument, "layer '" + change.layer + "' holds the privacy mask '" +
                                                             annotation.name + "', which cannot be hidden");
    if (renderer_)
        if (auto set = renderer_->setLayerEnabled(change.layer, change.visible); !set)
            return set;
    layerVisible_[change.layer] = change.visible;
    return Ok{};
}

SceneControl SceneControl::withScene(const OverlayScene &scene, const CameraSpec &camera) const
{
    SceneControl candidate = *this;
    candidate.load(scene, camera);
    candidate.detach();
    return candidate;
}

Status SceneControl::applyText(const TextChange &change)
{
    if (Status known = requireKnown("text slot", change.slot, textSlotNames(scene_)); !known)
        return known;
    if (Status checked = checkSlotText(change.text); !checked)
        return checked;
    if (renderer_)
        if (auto set = renderer_->setSlotText(change.slot, change.text); !set)
            return set;
    slotTexts_.insert_or_assign(change.slot, change.text);
    return Ok{};
}

Status SceneControl::applySteering(const SteeringChange &change)
{
    // The config's own limit for steering_deg.
    constexpr double kMaxRoadWheelDeg = 80.0;
    for (Annotation &annotation : scene_.annotations) {
        auto *guide = std::get_if<GuideLinesShape>(&annotation.shape);
        if (annotation.name != change.annotation || !guide)
            continue;
        std::optional<double> road;
        if (change.wheelDeg && std::isfinite(*change.wheelDeg))
            road = *change.wheelDeg / guide->steeringRatio;
        if (road && !(std::abs(*road) < kMaxRoadWheelDeg))
            road.reset();
        if (renderer_)
            if (auto set = renderer_->setGuideSteering(change.annotation, road); !set)
                return set;
        guide->steeringKnown = road.has_value();
        guide->steeringDeg = road.value_or(0.0);
        return Ok{};
    }
    return makeError(ErrorCode::InvalidArgument, "no guide-lines annotation named '" + change.annotation + "'");
}

Status SceneControl::applyPoints(const PointsChange &change)
{
    for (Annotation &annotation : scene_.annotations) {
        std::vector<glm::dvec3> *points = worldPointsOf(annotation);
        if (annotation.name != change.annotation || !points)
            continue;
        if (renderer_)
            if (auto set = renderer_->setWorldPoints(change.annotation, change.points); !set)
                return set;
        *points = change.points;
        return Ok{};
    }
    return makeError(ErrorCode::InvalidArgument, "no polyline or markers annotation named '" + change.annotation + "'");
}

std::vector<std::string> SceneControl::layerNames() const
{
    std::vector<std::string> names;
    for (const Annotation &annotation : scene_.annotations)
        if (std::find(names.begin(), names.end(), annotation.style.layer) == names.end())
            names.push_back(annotation.style.layer);
    return names;
}

std::string SceneControl::slotText(const std::string &slot) const
{
    const auto found = slotTexts_.find(slot);
    return found == slotTexts_.end() ? std::string() : found->second;
}

bool SceneControl::layerVisible(const std::string &layer) const
{
    const auto found = layerVisible_.find(layer);
    return found == layerVisible_.end() || found->second;
}

} // namespace overlayd
