// SPDX-License-Identifier: Apache-2.0
// SceneRenderer: the OverlayRenderer, made by SceneRenderer::create. One NativeLayer per named layer (so switching a
// layer off costs nothing and re-projects nothing): the layer is drawn on a full-frame RGBA canvas that all layers
// share and that lives only while they are rendered, and what it keeps are the runs of the pixels it covers, so its
// memory is proportional to what it draws. A screen text with tokens (a frame counter, a clock, a slot) keeps its
// background box as a small layer and its glyphs as stamps (GlyphStamps: each glyph a small layer kept where it was
// drawn, so a new string re-blends cached glyphs and makes only a glyph at a new place). One small layer per image,
// warped from its pixels again only when the camera (or the viewport) changes.
//
// A camera that keeps moving (setCamera before two blends in a row) is drawn straight into each frame instead:
// a cached layer would be redrawn and converted every frame for one use. When the camera holds still for a frame,
// the layers are rendered once more and the cached blend takes over again. A live steering angle takes the same path.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "overlay/blend/frame_coverage_sink.h"
#include "overlay/blend/native_layer.h"
#include "overlay/glyph_stamps.h"
#include "overlay/overlay_renderer.h"
#include "overlay/privacy_masks.h"
#include "overlay/raster/rasterizer.h"
#include "overlay/raster/text_renderer.h"
#include "overlay/shapes/text_tokens.h"

namespace overlayd {

class SceneRenderer final : public OverlayRenderer
{
public:
    // Configure time: validates the scene (unknown frames, non-finite values, widths, sizes) and renders it for a
    // stream. The camera's viewport must have the stream's frame size.
    static Result<std::unique_ptr<OverlayRenderer>> create(const OverlayScene &scene, const Camera &camera,
                                                           const StreamFormat &format);

    SceneRenderer(const OverlayScene &scene, SceneGraph graph, const Camera &camera, const StreamFormat &format);

    Status setCamera(const Camera &camera) override;
    Status setLayerEnabled(std::string_view layer, bool enabled) override;
    std::vector<std::string> layerNames() const override;
    Status setSlotText(std::string_view slot, std::string_view text) override;
    Status setGuideSteering(std::string_view annotation, std::optional<double> steeringDeg) override;
    Status setWorldPoints(std::string_view annotation, std::span<const glm::dvec3> points) override;
    Status applyMasks(const FrameView &frame) override;
    Status blend(const FrameView &frame, const FrameMetadata &metadata, double fps) override;

    // Rasterizes the privacy masks for the camera (called by create; setCamera does it for the new camera).
    Status renderMasks() { return masks_.setCamera(camera_, graph_); }
    // Re-projects and re-rasterizes every world layer (called by create and setCamera).
    Status renderWorld();
    // Whether the last blend drew the world straight into the frame (a moving camera), for tests and stats.
    bool drewDirectly() const { return drewDirectly_; }
    // The RGBA pixels of a named layer, drawn again for the current camera (the renderer keeps only their native
    // runs), for tests and previews; nothing for an unknown name.
    std::optional<OverlayLayer> layerPixels(std::string_view name);

private:
    struct Layer {
        std::string name;
        bool enabled = true;
        std::optional<NativeLayer> native;
        std::vector<size_t> annotations; // indices into scene_.annotations, in drawing order
    };
    struct ImageSprite {
        size_t annotation = 0;
        size_t layer = 0;
        bool rendered = false;
        std::optional<NativeLayer> native;
    };
    // A screen text with tokens: its background box as a layer (the same from one string to the next, re-rendered
    // only when the box moves or resizes) and its glyphs as stamps, each kept where it was drawn.
    struct TextSlot {
        size_t annotation = 0;
        size_t layer = 0;
        std::string shown, scratch;      // the expanded text drawn, and the next frame's
        bool built = false;              // items hold the primitives of `shown` for the current camera
        std::vector<TextItem> items;     // without their background, which is `box`
        std::vector<glm::ivec2> origins; // each item's box corner, laid out once per string
        std::optional<NativeLayer> box;
        FillItem boxFill;
        std::optional<GlyphStamps> stamps;
    };

    // The frame is the stream's: format, size and planes.
    Status checkStreamFrame(const FrameView &frame) const;
    Status buildText(TextSlot &slot);
    Status blendText(TextSlot &slot, const FrameView &frame);
    // The layer of a background box `fill` (slot.box), kept while the box stays the same.
    Status renderTextBox(TextSlot &slot, const FillItem &fill);
    // `list` drawn on a layer of `box` (frame pixels) widened to whole macropixels, kept as native runs placed on
    // the frame in `layer` (none when the box is off the frame or outside the scissor).
    Status drawPlaced(const DrawList &list, LayerRect box, std::optional<NativeLayer> &layer);
    Status renderImage(ImageSprite &sprite);
    Status blendImages(const FrameView &frame);
    // A frame-pixel box widened to whole macropixels and cut to the frame and the scissor.
    LayerRect macropixelBox(LayerRect box) const;
    // The moving-camera path: every enabled world layer projected and painted into this frame.
    void drawWorldInto(const FrameView &frame);
    Status blendTexts(const FrameView &frame, const FrameMetadata &metadata, double fps);
    // Paints a layer's annotations on a full-frame canvas (cleared) and finds its spans.
    void drawLayer(const Layer &layer, OverlayLayer &canvas);
    size_t layerIndex(const std::string &name);
    LayerRect scissor() const;
    LayerRect frameClip() const; // the scissor cut to the frame: what a draw straight into it may touch

    OverlayScene scene_;
    SceneGraph graph_;
    Camera camera_;
    StreamFormat format_;
    // From the stream format, not from each frame's metadata (sources that do not fill it in would flip the
    // conversion back and forth); a renegotiated stream gets a new renderer.
    Colorimetry colorimetry_;
    TextRenderer text_;
    Rasterizer rasterizer_;
    std::vector<Layer> layers_;
    std::vector<TextSlot> texts_;
    std::vector<ImageSprite> images_;
    PrivacyMasks masks_;                 // kept out of layers_: no layer switch reaches them
    std::vector<std::string> slotNames_; // the {slot:NAME} tokens the scene's texts use
    SlotTexts slotTexts_;
    FrameCoverageSink frameSink_;
    bool worldStale_ = false; // the camera changed since the layers were rendered
    bool cameraChangedSinceBlend_ = false;
    unsigned movingFrames_ = 0; // consecutive blends, each preceded by a camera change
    bool drewDirectly_ = false;
    DrawList drawList_; // scratch
};

} // namespace overlayd
