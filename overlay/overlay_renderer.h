// SPDX-License-Identifier: Apache-2.0
// OverlayRenderer: one stream's overlay. World annotations are projected and rasterized once per change of scene,
// camera or format; screen text whose tokens change (timestamp, frame number) lives on small layers of its own that
// are re-rendered only when their text changes; the per-frame work is the native-format blend. The interface the
// daemon holds; SceneRenderer::create (overlay/scene_renderer.h) makes the one implementation.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "media/frame.h"
#include "media/stream.h"
#include "overlay/shapes/annotation.h"
#include "projection/camera.h"

namespace overlayd {

class OverlayRenderer
{
public:
    virtual ~OverlayRenderer() = default;

    // The camera moved or changed (dynamic overlays): the next blend re-projects. A camera that changes before every
    // frame is drawn straight into each frame; one that then holds still is rendered into the cached layers again.
    virtual Status setCamera(const Camera &camera) = 0;
    // Layers are named by the annotations' styles; an unknown name is an InvalidArgument error.
    virtual Status setLayerEnabled(std::string_view layer, bool enabled) = 0;
    virtual std::vector<std::string> layerNames() const = 0;
    // What a {slot:NAME} token shows from the next frame on (checkSlotText's rules); an unknown slot is an
    // InvalidArgument error.
    virtual Status setSlotText(std::string_view slot, std::string_view text) = 0;
    // A guide-lines annotation's road-wheel steering angle (degrees, |angle| < 89) from the next frame on, or
    // nullopt when it is unknown (its wheel tracks go). Like a camera change, it re-projects the world layers:
    // drawn straight into frames while it keeps changing. An unknown annotation is an InvalidArgument error.
    virtual Status setGuideSteering(std::string_view annotation, std::optional<double> steeringDeg) = 0;
    // A polyline's or markers annotation's points (in its frame; at most kMaxWorldPoints, finite), re-projected like
    // a camera change. An unknown annotation or a bad point is an InvalidArgument error, and nothing changes.
    virtual Status setWorldPoints(std::string_view annotation, std::span<const glm::dvec3> points) = 0;

    // Frame path, before anything else reads the frame (the raw snapshot tap, the blend, every sink): burns the
    // scene's privacy masks into it. An error means the frame could not be masked and must not go out. A renderer
    // without masks has nothing to do.
    virtual Status applyMasks(const FrameView &frame)
    {
        (void)frame;
        return Ok{};
    }
    // Frame path (no exceptions; no allocation once the text layers have warmed up and while the camera holds
    // still): refreshes token text if it changed and blends every enabled layer into the frame in place. fps feeds
    // the {fps} token.
    virtual Status blend(const FrameView &frame, const FrameMetadata &metadata, double fps) = 0;
};

} // namespace overlayd
