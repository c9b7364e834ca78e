// SPDX-License-Identifier: Apache-2.0
// SceneControl: the one path by which the running scene changes. Every change is typed, validated by the code that
// validates the config file, applied on the loop thread between two frames and visible in the next frame.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "base/result.h"
#include "config/camera_spec.h"
#include "media/stream.h"
#include "overlay/overlay_renderer.h"
#include "overlay/shapes/annotation.h"
#include "overlay/shapes/text_tokens.h"

namespace overlayd {

// The camera moved or was re-calibrated: pose, intrinsics, lens and viewport, as [camera] and [viewport] give them.
struct CameraChange {
    CameraSpec camera;
};

// A named layer (an annotation style's `layer`) shown or hidden; the choice outlives renderer rebuilds.
struct LayerChange {
    std::string layer;
    bool visible = true;
};

// What a text slot shows: the scene's screen texts that hold {slot:NAME} show it from the next frame on (one line,
// at most kMaxSlotTextBytes); the text outlives renderer rebuilds.
struct TextChange {
    std::string slot;
    std::string text;
};

// A live steering-wheel angle for a guide-lines annotation (its steering_ratio turns it into the road-wheel angle),
// or nullopt when the angle is unknown: the wheel tracks go and the marks show straight, in the stale colour. A
// road-wheel angle the geometry cannot draw (80 degrees or more) counts as unknown. The angle outlives renderer
// rebuilds.
struct SteeringChange {
    std::string annotation;
    std::optional<double> wheelDeg;
};

// New points for a polyline or markers annotation (a path file changed): from the next frame on, outliving renderer
// rebuilds. No points is an empty path (nothing drawn).
struct PointsChange {
    std::string annotation;
    std::vector<glm::dvec3> points;
};

using SceneChange = std::variant<CameraChange, LayerChange, TextChange, SteeringChange, PointsChange>;

// Builds a stream's overlay from a scene and the camera resolved for the stream's frame size; null: nothing to draw.
using RendererFactory = std::function<Result<std::unique_ptr<OverlayRenderer>>(
    const OverlayScene &scene, const Camera &camera, const StreamFormat &format)>;

class SceneControl
{
public:
    explicit SceneControl(RendererFactory factory) : factory_(std::move(factory)) {}

    // The scene of a freshly loaded config, before any stream is open. Layer choices made so far are kept.
    void load(const OverlayScene &scene, const CameraSpec &camera);
    // The overlay for a newly opened stream: the live scene and camera for its frame size, with the live layer
    // choices applied. The caller hands it to the pipeline and then calls attach().
    Result<std::unique_ptr<OverlayRenderer>> build(const StreamFormat &format) const;
    // The renderer the pipeline now blends with (null: none), and its stream; changes go to it from now on.
    void attach(OverlayRenderer *renderer, const StreamFormat &format);
    void detach() { attach(nullptr, StreamFormat{}); }

    // Validates and applies a change. Refused (nothing changes) with the reason, as a config error would give it.
    Status apply(const SceneChange &change);
    // A reload's whole new scene and camera: a candidate control with them, the live layer choices and slot texts,
    // and no stream. The reload builds the new stream's overlay from it (build, cameraFor) and, once every other
    // part of the reload is ready too, assigns it over the live one and attaches the new overlay; a refused reload
    // drops it, and the live scene never saw it.
    SceneControl withScene(const OverlayScene &scene, const CameraSpec &camera) const;

    const CameraSpec &camera() const { return camera_; }
    // The live camera for a frame size, built once per size and camera change (the source that draws through it
    // and the overlay share one build).
    Result<Camera> cameraFor(unsigned width, unsigned height) const;
    const OverlayScene &scene() const { return scene_; }
    // Every layer the scene draws, in the order annotations first name them.
    std::vector<std::string> layerNames() const;
    bool layerVisible(const std::string &layer) const;
    // What a slot shows now (empty when never set).
    std::string slotText(const std::string &slot) const;

private:
    Status applyCamera(const CameraChange &change);
    Status applyLayer(const LayerChange &change);
    Status applyText(const TextChange &change);
    Status applySteering(const SteeringChange &change);
    Status applyPoints(const PointsChange &change);
    Result<std::unique_ptr<OverlayRenderer>> buildFor(const OverlayScene &scene, const Camera &camera,
                                                      const StreamFormat &format) const;

    RendererFactory factory_;
    OverlayScene scene_;
    CameraSpec camera_;
    std::map<std::string, bool, std::less<>> layerVisible_; // only the layers a change named
    SlotTexts slotTexts_;                                   // only the slots a change set
    OverlayRenderer *renderer_ = nullptr;                   // owned by the pipeline
    StreamFormat format_{};
    // The last cameraFor() build, while camera_ and its size stay the same.
    mutable std::optional<Camera> built_;
    mutable unsigned builtWidth_ = 0, builtHeight_ = 0;
};

} // namespace overlayd
