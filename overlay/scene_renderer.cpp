// SPDX-License-Identifier: Apache-2.0
// SceneRenderer: renders world layers on scene/camera/format changes and token text on text changes; the frame
// path is the blend of what is cached.
#include "overlay/scene_renderer.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <opencv2/core.hpp>

#include "overlay/raster/image_warp.h"
#include "overlay/shapes/image_quad.h"
#include "overlay/shapes/scene_checks.h"
#include "overlay/shapes/shape_builder.h"

namespace overlayd {

Result<std::unique_ptr<OverlayRenderer>> SceneRenderer::create(const OverlayScene &scene, const Camera &camera,
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

SceneRenderer::SceneRenderer(const OverlayScene &scene, SceneGraph graph, const Camera &camera,
                             const StreamFormat &format)
    : scene_(scene), graph_(std::move(graph)), camera_(camera), format_(format), colorimetry_(format.colorimetry),
      rasterizer_(text_), masks_(scene, format), frameSink_(*format.format, format.colorimetry)
{
    for (size_t i = 0; i < scene_.annotations.size(); ++i) {
        const Annotation &annotation = scene_.annotations[i];
        const size_t layer = layerIndex(annotation.style.layer); // a mask's too: showing it is no error
        if (isMask(annotation))
            continue;
        const auto *text = std::get_if<ScreenTextShape>(&annotation.shape);
        if (text && hasTokens(text->text)) {
            TextSlot &slot = texts_.emplace_back();
            slot.annotation = i;
            slot.layer = layer;
        } else if (std::holds_alternative<ImageShape>(annotation.shape)) {
            images_.push_back(ImageSprite{i, layer, false, std::nullopt});
        } else {
            layers_[layer].annotations.push_back(i);
        }
    }
    slotNames_ = textSlotNames(scene_);
}

size_t SceneRenderer::layerIndex(const std::string &name)
{
    for (size_t i = 0; i < layers_.size(); ++i) {
        if (layers_[i].name == name)
            return i;
    }
    layers_.push_back(Layer{name, true, std::nullopt, {}});
    return layers_.size() - 1;
}

LayerRect SceneRenderer::scissor() const
{
    const PixelRect r = camera_.viewport().scissorTopLeft();
    return {r.x, r.y, r.x + r.width, r.y + r.height};
}

void SceneRenderer::drawLayer(const Layer &layer, OverlayLayer &canvas)
{
    canvas.clearCovered();
    for (size_t index : layer.annotations) {
        const Annotation &annotation = scene_.annotations[index];
        const Result<glm::dmat4> worldFromFrame =
            isScreenText(annotation) ? Result<glm::dmat4>(glm::dmat4(1.0)) : graph_.worldMatrix(annotation.frame);
        const glm::dmat4 matrix = worldFromFrame ? *worldFromFrame : glm::dmat4(1.0); // screen items: no frame
        drawList_.clear();
        buildPrimitives(annotation, matrix, camera_, drawList_);
        rasterizer_.draw(drawList_, canvas, {0, 0}, scissor());
    }
    canvas.updateSpans();
}

Status SceneRenderer::renderWorld()
{
    worldStale_ = false;
    // One canvas for every layer, freed on return: fresh zero pages, so only the pages drawn on cost memory.
    OverlayLayer canvas(format_.width, format_.height);
    for (Layer &layer : layers_) {
        drawLayer(layer, canvas);
        if (layer.native) {
            if (Status status = layer.native->update(canvas, colorimetry_); !status)
                return status;
            continue;
        }
        auto native = NativeLayer::convert(canvas, *format_.format, colorimetry_);
        if (!native)
            return native.error();
        layer.native = std::move(*native);
    }
    for (TextSlot &slot : texts_)
        slot.built = false; // the viewport may have moved them
    for (ImageSprite &sprite : images_)
        sprite.rendered = false;
    return Ok{};
}

// The slot's primitives for its new string, kept in the slot (reused until the string or the camera changes, so a
// long string is not copied every frame); the background becomes the slot's box layer.
Status SceneRenderer::buildText(TextSlot &slot)
{
    drawList_.clear();
    buildPrimitives(scene_.annotations[slot.annotation], glm::dmat4(1.0), camera_, drawList_);
    slot.items.resize(drawList_.texts.size());
    slot.origins.resize(slot.items.size());
    slot.shown = slot.scratch;
    slot.built = true;
    for (size_t i = 0; i < slot.items.size(); ++i) { // one, a screen text's
        TextItem &item = slot.items[i];
        std::string text = std::move(item.text);
        item = std::move(drawList_.texts[i]);
        item.text = std::move(text);
        item.text.assign(slot.shown); // the annotation holds the text with its tokens
        const LayerRect box = rasterizer_.textBox(item);
        slot.origins[i] = {box.x0, box.y0};
        if (!item.background)
            continue;
        const LayerRect plate = rasterizer_.plateBox(item);
        if (Status status = renderTextBox(slot, FillItem{*item.background, plate.x0, plate.y0, plate.x1, plate.y1});
            !status)
            return status;
        item.background.reset();
    }
    return Ok{};
}

Status SceneRenderer::blendText(TextSlot &slot, const FrameView &frame)
{
    if (!slot.built || slot.scratch != slot.shown)
        if (Status status = buildText(slot); !status)
            return status;
    if (slot.box)
        slot.box->blendChecked(frame);
    if (!text_.usesFreeType()) { // the Hershey fallback has no glyphs of its own: drawn into the frame
        drawList_.clear();
        drawList_.texts = slot.items;
        frameSink_.setFrame(frame);
        rasterizer_.draw(drawList_, frameSink_, {0, 0}, frameClip());
        return Ok{};
    }
    if (!slot.stamps)
        slot.stamps.emplace(format_, colorimetry_);
    for (size_t i = 0; i < slot.items.size(); ++i)
        if (Status status = slot.stamps->blend(text_, slot.items[i], slot.origins[i], frameClip(), frame); !status)
            return status;
    return Ok{};
}

Status SceneRenderer::renderTextBox(TextSlot &slot, const FillItem &fill)
{
    const FillItem &was = slot.boxFill;
    if (slot.box && was.colour == fill.colour && was.x0 == fill.x0 && was.y0 == fill.y0 && was.x1 == fill.x1 &&
        was.y1 == fill.y1)
        return Ok{};
    slot.boxFill = fill;
    DrawList boxList;
    boxList.fills.push_back(fill);
    return drawPlaced(boxList, {fill.x0, fill.y0, fill.x1, fill.y1}, slot.box);
}

Status SceneRenderer::drawPlaced(const DrawList &list, LayerRect box, std::optional<NativeLayer> &layer)
{
    layer.reset();
    const auto [x0, y0, x1, y1] = macropixelBox(box);
    if (x0 >= x1 || y0 >= y1)
        return Ok{};
    OverlayLayer pixels(unsigned(x1 - x0), unsigned(y1 - y0));
    rasterizer_.draw(list, pixels, {x0, y0}, scissor());
    pixels.updateSpans();
    auto native = NativeLayer::convert(pixels, *format_.format, colorimetry_,
                                       {unsigned(x0), unsigned(y0), format_.width, format_.height});
    if (!native)
        return native.error();
    layer = std::move(*native);
    return Ok{};
}

// The image's quad, widened to whole macropixels, becomes a layer of its own placed on the frame.
Status SceneRenderer::renderImage(ImageSprite &sprite)
{
    sprite.rendered = true;
    sprite.native.reset();
    const Annotation &annotation = scene_.annotations[sprite.annotation];
    const auto &shape = std::get<ImageShape>(annotation.shape);
    glm::dmat4 worldFromFrame(1.0);
    if (shape.anchor) {
        const Result<glm::dmat4> matrix = graph_.worldMatrix(annotation.frame);
        if (!matrix)
            return matrix.error();
        worldFromFrame = *matrix;
    }
    std::optional<std::array<glm::dvec2, 4>> quad = imageQuad(shape, worldFromFrame, camera_);
    if (!quad)
        return Ok{};
    glm::dvec2 low = (*quad)[0], high = (*quad)[0];
    for (const glm::dvec2 &corner : *quad)
        low = glm::min(low, corner), high = glm::max(high, corner);
    constexpr double kFar = 1e6; // corners far outside the frame (a plane nearly edge-on) before the int cast
    low = glm::clamp(low, glm::dvec2(-kFar), glm::dvec2(kFar)),
    high = glm::clamp(high, glm::dvec2(-kFar), glm::dvec2(kFar));
    const auto [x0, y0, x1, y1] = macropixelBox({int(std::floor(low.x + 0.5)), int(std::floor(low.y + 0.5)),
                                                 int(std::ceil(high.x + 0.5)), int(std::ceil(high.y + 0.5))});
    if (x0 >= x1 || y0 >= y1)
        return Ok{};
    OverlayLayer pixels(unsigned(x1 - x0), unsigned(y1 - y0));
    for (glm::dvec2 &corner : *quad)
        corner -= glm::dvec2(x0, y0);
    try {
        if (!warpImage(*shape.image, *quad, shape.opacity, pixels))
            return Ok{};
    } catch (const cv::Exception &error) { // a homography OpenCV cannot use: the image is left out, not the frame
        return Ok{};
    }
    pixels.updateSpans();
    auto native = NativeLayer::convert(pixels, *format_.format, colorimetry_,
                                       {unsigned(x0), unsigned(y0), format_.width, format_.height});
    if (!native)
        return native.error();
    sprite.native = std::move(*native);
    return Ok{};
}

Status SceneRenderer::blendImages(const FrameView &frame)
{
    for (ImageSprite &sprite : images_) {
        if (!layers_[sprite.layer].enabled)
            continue;
        if (!sprite.rendered)
            if (Status status = renderImage(sprite); !status)
                return status;
        if (sprite.native)
            sprite.native->blendChecked(frame);
    }
    return Ok{};
}

LayerRect SceneRenderer::frameClip() const
{
    return scissor().intersect({0, 0, int(format_.width), int(format_.height)});
}

LayerRect SceneRenderer::macropixelBox(LayerRect box) const
{
    return macropixelAligned(box.intersect(scissor()), *format_.format, format_.width, format_.height);
}

Status SceneRenderer::setCamera(const Camera &camera)
{
    if (camera.viewport().frameWidth() != int(format_.width) || camera.viewport().frameHeight() != int(format_.height))
        return makeError(ErrorCode::InvalidArgument, "the camera's viewport is not the stream's " +
                                                         std::to_string(format_.width) + "x" +
                                                         std::to_string(format_.height));
    if (Status masked = masks_.setCamera(camera, graph_); !masked)
        return masked;
    camera_ = camera;
    worldStale_ = true;
    cameraChangedSinceBlend_ = true;
    for (TextSlot &slot : texts_) {
        slot.built = false; // the viewport may have moved them, and its scissor cut stamps differently
        slot.stamps.reset();
    }
    for (ImageSprite &sprite : images_)
        sprite.rendered = false;
    return Ok{};
}

Status SceneRenderer::setGuideSteering(std::string_view annotation, std::optional<double> steeringDeg)
{
    if (steeringDeg && !(std::abs(*steeringDeg) < 89.0))
        return makeError(ErrorCode::InvalidArgument, "a steering angle must be finite and below 89 degrees");
    for (Annotation &a : scene_.annotations) {
        auto *guide = std::get_if<GuideLinesShape>(&a.shape);
        if (a.name != annotation || !guide)
            continue;
        if (guide->steeringKnown == steeringDeg.has_value() && guide->steeringDeg == steeringDeg.value_or(0.0))
            return Ok{};
        guide->steeringKnown = steeringDeg.has_value();
        guide->steeringDeg = steeringDeg.value_or(0.0);
        worldStale_ = true;
        cameraChangedSinceBlend_ = true;
        return Ok{};
    }
    return makeError(ErrorCode::InvalidArgument, "no guide-lines annotation named \"" + std::string(annotation) + "\"");
}

Status SceneRenderer::setWorldPoints(std::string_view annotation, std::span<const glm::dvec3> points)
{
    if (points.size() > kMaxWorldPoints)
        return makeError(ErrorCode::InvalidArgument, "at most " + std::to_string(kMaxWorldPoints) + " points");
    for (const glm::dvec3 &p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return makeError(ErrorCode::InvalidArgument, "points must be finite");
    for (Annotation &a : scene_.annotations) {
        std::vector<glm::dvec3> *target = worldPointsOf(a);
        if (a.name != annotation || !target)
            continue;
        target->assign(points.begin(), points.end());
        worldStale_ = true;
        cameraChangedSinceBlend_ = true;
        return Ok{};
    }
    return makeError(ErrorCode::InvalidArgument,
                     "no polyline or markers annotation named \"" + std::string(annotation) + "\"");
}

Status SceneRenderer::setLayerEnabled(std::string_view name, bool enabled)
{
    for (const Annotation &annotation : scene_.annotations)
        if (!enabled && isMask(annotation) && annotation.style.layer == name)
            return makeError(ErrorCode::InvalidArgument, "layer \"" + std::string(name) +
                                                             "\" holds the privacy mask \"" + annotation.name +
                                                             "\", which cannot be hidden");
    for (Layer &layer : layers_) {
        if (layer.name == name) {
            layer.enabled = enabled;
            return Ok{};
        }
    }
    return makeError(ErrorCode::InvalidArgument, "no overlay layer named \"" + std::string(name) + "\"");
}

Status SceneRenderer::setSlotText(std::string_view slot, std::string_view text)
{
    if (std::find(slotNames_.begin(), slotNames_.end(), slot) == slotNames_.end())
        return makeError(ErrorCode::InvalidArgument, "no text shows a slot named \"" + std::string(slot) + "\"");
    if (Status checked = checkSlotText(text); !checked)
        return checked;
    // The token texts that show it are re-rendered on the next blend, when their expanded string differs.
    slotTexts_.insert_or_assign(std::string(slot), std::string(text));
    return Ok{};
}

std::vector<std::string> SceneRenderer::layerNames() const
{
    std::vector<std::string> names;
    for (const Layer &layer : layers_)
        names.push_back(layer.name);
    return names;
}

std::optional<OverlayLayer> SceneRenderer::layerPixels(std::string_view name)
{
    for (const Layer &layer : layers_) {
        if (layer.name != name)
            continue;
        OverlayLayer canvas(format_.width, format_.height);
        drawLayer(layer, canvas);
        return canvas;
    }
    return std::nullopt;
}

void SceneRenderer::drawWorldInto(const FrameView &frame)
{
    frameSink_.setFrame(frame);
    const LayerRect clip = frameClip();
    for (const Layer &layer : layers_) {
        if (!layer.enabled)
            continue;
        for (size_t index : layer.annotations) {
            const Annotation &annotation = scene_.annotations[index];
            const Result<glm::dmat4> worldFromFrame =
                isScreenText(annotation) ? Result<glm::dmat4>(glm::dmat4(1.0)) : graph_.worldMatrix(annotation.frame);
            drawList_.clear();
            buildPrimitives(annotation, worldFromFrame ? *worldFromFrame : glm::dmat4(1.0), camera_, drawList_);
            rasterizer_.draw(drawList_, frameSink_, {0, 0}, clip);
        }
    }
}

Status SceneRenderer::checkStreamFrame(const FrameView &frame) const
{
    if (!frame.format || frame.format->fourcc != format_.format->fourcc || frame.width != format_.width ||
        frame.height != format_.height)
        return makeError(ErrorCode::InvalidArgument, "frame does not match the overlay's " + format_.describe());
    return checkFrame(frame);
}

Status SceneRenderer::applyMasks(const FrameView &frame)
{
    if (masks_.empty())
        return Ok{};
    if (Status status = checkStreamFrame(frame); !status)
        return status;
    masks_.apply(frame);
    return Ok{};
}

Status SceneRenderer::blend(const FrameView &frame, const FrameMetadata &metadata, double fps)
{
    // Checked once here; every layer below blends without checking again.
    if (Status status = checkStreamFrame(frame); !status)
        return status;
    movingFrames_ = cameraChangedSinceBlend_ ? movingFrames_ + 1 : 0;
    cameraChangedSinceBlend_ = false;
    drewDirectly_ = worldStale_ && movingFrames_ >= 2;
    if (drewDirectly_) {
        drawWorldInto(frame);
        if (Status status = blendImages(frame); !status)
            return status;
        return blendTexts(frame, metadata, fps);
    }
    if (worldStale_) {
        if (Status status = renderWorld(); !status)
            return status;
    }
    for (const Layer &layer : layers_) {
        if (layer.enabled && layer.native)
            layer.native->blendChecked(frame);
    }
    if (Status status = blendImages(frame); !status)
        return status;
    return blendTexts(frame, metadata, fps);
}

Status SceneRenderer::blendTexts(const FrameView &frame, const FrameMetadata &metadata, double fps)
{
    for (TextSlot &slot : texts_) {
        if (!layers_[slot.layer].enabled)
            continue;
        expandTokens(std::get<ScreenTextShape>(scene_.annotations[slot.annotation].shape).text, metadata, fps,
                     slot.scratch, &slotTexts_);
        if (Status status = blendText(slot, frame); !status)
            return status;
    }
    return Ok{};
}

} // namespace overlayd
