// Rasterizer: draws projected primitives into an OverlayLayer with OpenCV, through a coverage mask per item.
#pragma once

#include <glm/vec2.hpp>
#include <opencv2/core.hpp>

#include "overlay/coverage.h"
#include "overlay/overlay_layer.h"
#include "overlay/primitives.h"
#include "overlay/text_renderer.h"

namespace overlayd {

class Rasterizer
{
public:
    explicit Rasterizer(const TextRenderer &text) : text_(text) {}

    // Draws the list over what the layer holds. Primitives are in frame pixels (memory order); the layer's pixel
    // (0, 0) is frame pixel `layerOrigin`, and nothing is drawn outside `clip` (frame pixels, e.g. the scissor).
    void draw(const DrawList &list, OverlayLayer &layer, glm::ivec2 layerOrigin, const LayerRect &clip);

    // The box a text item occupies, in frame pixels.
    LayerRect textBox(const TextItem &item) const;

private:
    void drawStroke(const StrokeItem &item, OverlayLayer &layer, glm::ivec2 origin, const LayerRect &clip);
    void drawText(const TextItem &item, OverlayLayer &layer, glm::ivec2 origin, const LayerRect &clip);
    void strokePolyline(std::span<const glm::dvec2> line, glm::dvec2 shift, const StrokeStyle &style, cv::Mat &target,
                        const cv::Scalar &colour);

    const TextRenderer &text_;
    cv::Mat mask_;     // scratch coverage, at least the layer's size; all zero between items
    Polylines dashed_; // scratch
};

} // namespace overlayd
