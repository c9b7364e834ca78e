// SPDX-License-Identifier: Apache-2.0
// Ray tracing of the checker ground. Unprojecting through a distorting lens is iterative and costs over a
// microsecond. So 4x4 blocks are tried first from their four corners; in blocks that hold an edge, each pixel's
// corners are traced, and pixels whose corners fall in different squares are supersampled from the corners (or
// traced sample by sample where the horizon crosses them); pixels that see much of a square at once, toward the
// horizon, take the checker's exact average over their footprint, as a camera's lens and sensor would.
#include "drivers/synthetic/checker_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/common.hpp>

#include "drivers/synthetic/scene_tracer.h"

namespace overlayd {

namespace {

constexpr unsigned kBlock = 4; // pixels per side of the blocks tried as one colour first
// Footprints at least this wide (in squares) are box-filtered; narrower ones, near the camera, are supersampled,
// which keeps their edges as sharp as the footprint itself.
constexpr double kFootprintFiltered = 0.25;

const uint8_t *colourOf(const Square &square)
{
    if (!square.ground)
        return kSceneSky;
    return ((square.i + square.j) & 1) ? kSceneDark : kSceneLight;
}

// The corners of one pixel: top-left, top-right, bottom-left, bottom-right.
struct PixelCorners {
    const Hit &tl, &tr, &bl, &br;

    bool allGround() const { return tl.ground && tr.ground && bl.ground && br.ground; }
    // Inside a pixel whose corners all see the ground, the pixel -> ground map is smooth (a homography bent
    // slightly by the lens), so bilinear interpolation of the corners' hits places the sub-samples to far below
    // a pixel; pixels touching the horizon are traced sample by sample instead.
    Hit interpolate(double fx, double fy) const
    {
        const glm::dvec2 top = tl.point + fx * (tr.point - tl.point), bottom = bl.point + fx * (br.point - bl.point);
        return {true, top + fy * (bottom - top)};
    }
};

// The share of dark along one axis near t (in squares), seen through a tent filter of half-width w: the filter a
// pixel sees the ground through is about that wide, and a tent (a box convolved with itself) leaves far less of the
// checker's pattern behind than a box does. Exact: the second integral of the square wave t -> floor(t) mod 2 is
// piecewise quadratic, and the tent's average is its second difference over w squared.
double oddShare(double t, double w)
{
    const auto twiceIntegrated = [](double x) {
        const double k = std::floor(x / 2.0), r = x - 2.0 * k, over = std::max(0.0, r - 1.0);
        return k * k - 0.5 * k + k * r + 0.5 * over * over;
    };
    return (twiceIntegrated(t + w) - 2.0 * twiceIntegrated(t) + twiceIntegrated(t - w)) / (w * w);
}

// A pixel whose footprint on the ground spans much of a square, toward the horizon: point samples (however many)
// alias into moire there, so its colour is the filtered checker instead, with the footprint's extent along each
// ground axis as the filter's half-width (dark where exactly one of the column and the row is odd).
bool blendFootprint(const PixelCorners &corners, double squareMetres, uint8_t *px)
{
    const glm::dvec2 lo =
        glm::min(glm::min(corners.tl.point, corners.tr.point), glm::min(corners.bl.point, corners.br.point));
    const glm::dvec2 hi =
        glm::max(glm::max(corners.tl.point, corners.tr.point), glm::max(corners.bl.point, corners.br.point));
    const glm::dvec2 centre = 0.5 * (lo + hi) / squareMetres, extent = (hi - lo) / squareMetres;
    if (std::max(extent.x, extent.y) < kFootprintFiltered)
        return false;
    const double oddX = oddShare(centre.x, std::max(extent.x, 1e-3)),
                 oddY = oddShare(centre.y, std::max(extent.y, 1e-3));
    const double dark = oddX * (1.0 - oddY) + oddY * (1.0 - oddX);
    for (unsigned k = 0; k < 3; ++k)
        px[k] = uint8_t(std::lround(kSceneLight[k] + dark * (double(kSceneDark[k]) - kSceneLight[k])));
    return true;
}

void supersample(const SceneTracer &tracer, const PixelCorners &corners, unsigned x, unsigned y, uint8_t *px)
{
    constexpr unsigned n = kSceneSupersampling;
    const bool interpolate = corners.allGround();
    if (interpolate && blendFootprint(corners, tracer.squareMetres(), px))
        return;
    unsigned sum[3] = {0, 0, 0};
    for (unsigned j = 0; j < n; ++j) {
        for (unsigned i = 0; i < n; ++i) {
            const double fx = (i + 0.5) / n, fy = (j + 0.5) / n;
            const Hit hit = interpolate ? corners.interpolate(fx, fy) : tracer.trace(x + fx - 0.5, y + fy - 0.5);
            const uint8_t *c = colourOf(tracer.square(hit));
            sum[0] += c[0], sum[1] += c[1], sum[2] += c[2];
        }
    }
    for (unsigned k = 0; k < 3; ++k)
        px[k] = uint8_t((sum[k] + n * n / 2) / (n * n));
}

// Corner hits of a band of kBlock pixel rows, traced on demand: rows [y0, y0 + kBlock] of corners, x in [0, width].
class CornerBand
{
public:
    CornerBand(const SceneTracer &tracer, unsigned width) : tracer_(tracer)
    {
        for (auto &row : hits_)
            row.resize(width + 1);
        for (auto &row : known_)
            row.assign(width + 1, false);
    }

    // Moves to the band starting at corner row y0; the previous band's last row becomes this band's first.
    void advance(unsigned y0)
    {
        std::swap(hits_[0], hits_[kBlock]);
        std::swap(known_[0], known_[kBlock]);
        for (unsigned r = 1; r <= kBlock; ++r)
            std::fill(known_[r].begin(), known_[r].end(), false);
        y0_ = y0;
    }

    const Hit &at(unsigned x, unsigned y)
    {
        const unsigned r = y - y0_;
        if (!known_[r][x]) {
            hits_[r][x] = tracer_.trace(x - 0.5, y - 0.5);
            known_[r][x] = true;
        }
        return hits_[r][x];
    }

private:
    const SceneTracer &tracer_;
    unsigned y0_ = 0;
    std::array<std::vector<Hit>, kBlock + 1> hits_;
    std::array<std::vector<bool>, kBlock + 1> known_;
};

void fill(RgbImage &image, unsigned x0, unsigned x1, unsigned y0, unsigned y1, const uint8_t *colour)
{
    for (unsigned y = y0; y < y1; ++y) {
        uint8_t *px = image.row(y) + 3 * x0;
        for (unsigned x = x0; x < x1; ++x, px += 3)
            px[0] = colour[0], px[1] = colour[1], px[2] = colour[2];
    }
}

void renderPixel(const SceneTracer &tracer, CornerBand &band, unsigned x, unsigned y, uint8_t *px)
{
    const PixelCorners corners{band.at(x, y), band.at(x + 1, y), band.at(x, y + 1), band.at(x + 1, y + 1)};
    const Square square = tracer.square(corners.tl);
    if (square == tracer.square(corners.tr) && square == tracer.square(corners.bl) &&
        square == tracer.square(corners.br)) {
        const uint8_t *c = colourOf(square);
        px[0] = c[0], px[1] = c[1], px[2] = c[2];
    } else {
        supersample(tracer, corners, x, y, px);
    }
}

// A block whose four corners see the same square is that square throughout: a square is convex and the block's
// footprint on the ground is (to far below a pixel, even through a lens) the quadrilateral of its corners.
void renderBlock(const SceneTracer &tracer, CornerBand &band, RgbImage &image, unsigned x0, unsigned x1, unsigned y0,
                 unsigned y1)
{
    const Square square = tracer.square(band.at(x0, y0));
    if (square == tracer.square(band.at(x1, y0)) && square == tracer.square(band.at(x0, y1)) &&
        square == tracer.square(band.at(x1, y1))) {
        fill(image, x0, x1, y0, y1, colourOf(square));
        return;
    }
    for (unsigned y = y0; y < y1; ++y) {
        for (unsigned x = x0; x < x1; ++x)
            renderPixel(tracer, band, x, y, image.row(y) + 3 * x);
    }
}

} // namespace

RgbImage renderCheckerScene(const Camera &camera, unsigned width, unsigned height, double squareMetres)
{
    const SceneTracer tracer(camera, squareMetres);
    RgbImage image = RgbImage::allocate(width, height);
    CornerBand band(tracer, width);
    for (unsigned y0 = 0; y0 < height; y0 += kBlock) {
        band.advance(y0);
        const unsigned y1 = std::min(y0 + kBlock, height);
        for (unsigned x0 = 0; x0 < width; x0 += kBlock)
            renderBlock(tracer, band, image, x0, std::min(x0 + kBlock, width), y0, y1);
    }
    return image;
}

} // namespace overlayd
