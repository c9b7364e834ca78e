// NoSignalFrame: OpenCV text on an opaque layer; blending an opaque layer replaces every byte of the frame, so the
// frame needs no format-specific fill.
#include "daemon/no_signal.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "overlay/blend/native_layer.h"
#include "overlay/raster/overlay_layer.h"

namespace overlayd {

namespace {

void drawCentred(cv::Mat &image, const std::string &text, double y, double scale, int thickness)
{
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
    const cv::Point origin((image.cols - size.width) / 2, int(y) + size.height / 2);
    cv::putText(image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255, 255), thickness,
                cv::LINE_AA);
}

void drawLayer(OverlayLayer &layer, const std::string &reason)
{
    layer.fillRect(0, 0, int(layer.width()), int(layer.height()), Rgba{48, 48, 48, 255});
    cv::Mat image(int(layer.height()), int(layer.width()), CV_8UC4, layer.data(), layer.stride());
    // Text scales with the frame so that it reads the same on 320x240 and 1920x1080.
    const double scale = std::max(0.3, layer.width() / 640.0);
    drawCentred(image, "NO SIGNAL", layer.height() * 0.42, 1.6 * scale, std::max(1, int(3 * scale)));
    // The reason may be long (a device path and an errno text): shrink it to fit the width.
    double reasonScale = 0.6 * scale;
    int baseline = 0;
    while (reasonScale > 0.2 &&
           cv::getTextSize(reason, cv::FONT_HERSHEY_SIMPLEX, reasonScale, 1, &baseline).width > int(layer.width()) - 8)
        reasonScale *= 0.9;
    drawCentred(image, reason, layer.height() * 0.6, reasonScale, 1);
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
