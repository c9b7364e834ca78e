// SPDX-License-Identifier: Apache-2.0
#include "overlay/raster/image_warp.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>

namespace overlayd {

namespace {

// Premultiplied "over": dst = src + dst * (1 - src.a), per channel, rounded.
void compositeOver(const cv::Mat &source, OverlayLayer &layer)
{
    for (int y = 0; y < source.rows; ++y) {
        const uint8_t *s = source.ptr<uint8_t>(y);
        uint8_t *d = layer.data() + size_t(y) * layer.stride();
        for (int i = 0; i < source.cols * 4; i += 4) {
            const unsigned keep = 255u - s[i + 3];
            for (int c = 0; c < 4; ++c)
                d[i + c] = uint8_t(s[i + c] + (d[i + c] * keep + 127) / 255);
        }
    }
}

} // namespace

bool warpImage(const ImagePixels &image, const std::array<glm::dvec2, 4> &quad, double opacity, OverlayLayer &layer)
{
    // Convex, one winding, and at least a pixel of area: the cross products of consecutive edges share one sign.
    double area = 0.0;
    int positive = 0, negative = 0;
    for (size_t i = 0; i < 4; ++i) {
        const glm::dvec2 a = quad[i], b = quad[(i + 1) % 4], c = quad[(i + 2) % 4];
        const double turn = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
        (turn > 0 ? positive : negative) += 1;
        area += a.x * b.y - b.x * a.y;
    }
    if ((positive != 4 && negative != 4) || std::abs(area) < 2.0 || !std::isfinite(area))
        return false;
    cv::Mat source(int(image.height), int(image.width), CV_8UC4, const_cast<uint8_t *>(image.rgba.data()));
    // The drawn size along the image's rows and columns (the longer of each pair of opposite edges).
    const double across = std::max(glm::distance(quad[0], quad[1]), glm::distance(quad[3], quad[2]));
    const double down = std::max(glm::distance(quad[0], quad[3]), glm::distance(quad[1], quad[2]));
    cv::Mat reduced;
    if (across < 0.5 * image.width || down < 0.5 * image.height) {
        const cv::Size size(std::max(1, int(std::ceil(across))), std::max(1, int(std::ceil(down))));
        cv::resize(source, reduced, cv::Size(std::min(size.width, source.cols), std::min(size.height, source.rows)), 0,
                   0, cv::INTER_AREA);
        source = reduced;
    }
    const double w = source.cols, h = source.rows;
    const cv::Point2f from[4] = {
        {-0.5f, -0.5f}, {float(w - 0.5), -0.5f}, {float(w - 0.5), float(h - 0.5)}, {-0.5f, float(h - 0.5)}};
    cv::Point2f to[4];
    for (int i = 0; i < 4; ++i)
        to[i] = cv::Point2f(float(quad[size_t(i)].x), float(quad[size_t(i)].y));
    const cv::Mat homography = cv::getPerspectiveTransform(from, to);
    cv::Mat warped;
    cv::warpPerspective(source, warped, homography, cv::Size(int(layer.width()), int(layer.height())), cv::INTER_LINEAR,
                        cv::BORDER_CONSTANT, cv::Scalar(0, 0, 0, 0));
    if (opacity < 1.0)
        warped.convertTo(warped, CV_8UC4, opacity);
    compositeOver(warped, layer);
    return true;
}

} // namespace overlayd
