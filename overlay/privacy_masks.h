// SPDX-License-Identifier: Apache-2.0
// PrivacyMasks: a scene's mask annotations, burned into each frame before anything else reads it. Each mask's
// polygon is rasterized to whole macropixels when the camera changes (a world mask is projected through it, so it
// stays on its object), and per frame its spans are filled or pixelated in the frame's own format. No layer switch
// reaches a mask: SceneControl refuses to hide a layer that holds one, and the renderer keeps masks out of layers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "media/stream.h"
#include "overlay/blend/mask_painter.h"
#include "overlay/raster/polygon_spans.h"
#include "overlay/shapes/annotation.h"
#include "projection/camera.h"
#include "projection/scene_graph.h"

namespace overlayd {

class PrivacyMasks
{
public:
    // The scene's masks, in drawing order; the rest of the scene is not looked at.
    PrivacyMasks(const OverlayScene &scene, const StreamFormat &format);

    bool empty() const { return masks_.empty(); }
    // Rasterizes every mask for the camera (screen masks too: the viewport's origin places them). Refused when a
    // world mask cannot be projected (an unknown frame, a lens that sees behind the camera), and then nothing
    // changes.
    Status setCamera(const Camera &camera, const SceneGraph &graph);
    // Frame path: the frame was checked against the stream's format and size; no allocation.
    void apply(const FrameView &frame);
    // The pixels mask `index` covers, for tests.
    const SpanRows &spans(size_t index) const { return masks_[index].rows; }

private:
    struct Mask {
        std::string name, frame;
        MaskShape shape;
        SpanRows rows;
    };

    Result<SpanRows> rasterize(const Mask &mask, const Camera &camera, const SceneGraph &graph) const;

    std::vector<Mask> masks_;
    unsigned width_, height_;
    MaskPainter painter_;
};

} // namespace overlayd
