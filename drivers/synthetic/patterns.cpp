// SPDX-License-Identifier: Apache-2.0
// The 2D patterns. Everything is integer arithmetic on the pixel position (and frame number), so output bytes do
// not depend on the compiler or machine.
#include "drivers/synthetic/patterns.h"

#include <cstring>
#include <vector>

namespace overlayd {

namespace {

void setPixel(uint8_t *px, const uint8_t *colour)
{
    px[0] = colour[0], px[1] = colour[1], px[2] = colour[2];
}

uint64_t splitmix64(uint64_t &state)
{
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

} // namespace

unsigned barEdge(unsigned bar, unsigned width)
{
    return bar >= 8 ? width : (bar * width / 8) & ~1u;
}

RgbImage colourBars(unsigned width, unsigned height)
{
    RgbImage image = RgbImage::allocate(width, height);
    uint8_t *row = image.row(0);
    for (unsigned bar = 0; bar < 8; ++bar) {
        for (unsigned x = barEdge(bar, width); x < barEdge(bar + 1, width); ++x)
            setPixel(row + 3 * x, kBarColours[bar]);
    }
    for (unsigned y = 1; y < height; ++y)
        std::memcpy(image.row(y), row, size_t(width) * 3);
    return image;
}

RgbImage checkerboard(unsigned width, unsigned height, unsigned squarePx)
{
    static constexpr uint8_t kWhite[3] = {255, 255, 255}, kBlack[3] = {0, 0, 0};
    RgbImage image = RgbImage::allocate(width, height);
    for (unsigned y = 0; y < height; ++y) {
        uint8_t *row = image.row(y);
        for (unsigned x = 0; x < width; ++x)
            setPixel(row + 3 * x, ((x / squarePx + y / squarePx) & 1) ? kBlack : kWhite);
    }
    return image;
}

void movingGradient(RgbImage &image, uint64_t frame)
{
    const unsigned w = image.width, h = image.height;
    // Red depends on the scrolled column u only, blue on u + y: tables keep divisions out of the pixel loop.
    std::vector<uint8_t> red(w), blue(size_t(w) + h);
    for (unsigned u = 0; u < w; ++u)
        red[u] = uint8_t(uint64_t(u) * 255 / w);
    for (size_t s = 0; s < blue.size(); ++s)
        blue[s] = uint8_t(s * 255 / blue.size());
    const unsigned shift = unsigned(frame * kGradientStepPx % w);
    for (unsigned y = 0; y < h; ++y) {
        uint8_t *px = image.row(y);
        const uint8_t green = uint8_t(uint64_t(y) * 255 / h);
        for (unsigned x = 0, u = shift; x < w; ++x, px += 3, u = u + 1 == w ? 0 : u + 1)
            px[0] = red[u], px[1] = green, px[2] = blue[u + y];
    }
}

void noise(RgbImage &image, uint64_t seed, uint64_t frame)
{
    uint64_t state = seed * 0x2545f4914f6cdd1dull ^ frame;
    uint64_t bits = 0;
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        if (i % 8 == 0)
            bits = splitmix64(state);
        image.rgb[i] = uint8_t(bits >> (8 * (i % 8)));
    }
}

} // namespace overlayd
