// SPDX-License-Identifier: Apache-2.0
// NoSignalFrame: the overlay's own text (the glyph cache, DejaVu Sans) on an opaque layer; blending an opaque layer
// replaces every byte of the frame, so the frame needs no format-specific fill.
#include "daemon/no_signal.h"

#include <algorithm>

#include "overlay/blend/native_layer.h"
#include "overlay/raster/overlay_layer.h"
#include "overlay/raster/rasterizer.h"
#include "overlay/raster/text_renderer.h"
#include "overlay/shapes/primitives.h"

namespace overlayd {

namespace {

constexpr Rgba kBackground{48, 48, 48, 255};
constexpr Rgba kText{255, 255, 255, 255};

TextItem centred(const TextRenderer &text, const std::string &line, unsigned width, double centreY, double sizePx)
{
    const TextRenderer::Box box = text.measure(line, sizePx);
    TextItem item;
    item.text = line;
    item.sizePx = sizePx;
    item.colour = kText;
    item.anchor = {std::max(0.0, (double(width) - box.width) / 2.0), centreY - box.height() / 2.0};
    return item;
}

void drawLayer(OverlayLayer &layer, const std::string &reason)
{
    layer.fillRect(0, 0, int(layer.width()), int(layer.height()), kBackground);
    const TextRenderer text;
    // Text scales with the frame so that it reads the same on 320x240 and 1920x1080.
    const double height = layer.height();
    DrawList list;
    list.texts.push_back(centred(text, "NO SIGNAL", layer.width(), height * 0.42, std::max(12.0, height * 0.12)));
    // The reason may be long (a device path and an errno text): shrink it to fit the width.
    double reasonSize = std::max(8.0, height * 0.05);
    while (reasonSize > 6.0 && text.measure(reason, reasonSize).width > int(layer.width()) - 8)
        reasonSize *= 0.9;
    list.texts.push_back(centred(text, reason, layer.width(), height * 0.6, reasonSize));
    Rasterizer(text).draw(list, layer, {0, 0}, {0, 0, int(layer.width()), int(layer.height())});
    layer.updateSpans();
}

} // namespace

Result<NoSignalFrame> NoSignalFrame::create(const StreamFormat &format, const std::string &reason)
{
    auto buffer = FrameBuffer::allocate(format);
    if (!buffer)
        return buffer.error();
    OverlayLayer layer(format.width, format.height);
    drawLayer(layer, reason);
    auto native = NativeLayer::convert(layer, *format.format, format.colorimetry);
    if (!native)
        return native.error();
    if (auto blended = native->blend(buffer->view()); !blended)
        return blended.error();
    return NoSignalFrame(std::move(*buffer), format, reason);
}

} // namespace overlayd
