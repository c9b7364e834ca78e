// SPDX-License-Identifier: Apache-2.0
// OverlayLayer storage, rectangle fills and the coverage scan.
#include "overlay/raster/overlay_layer.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <new>

namespace overlayd {

namespace {

uint8_t *zeroedBytes(size_t size)
{
    auto *bytes = static_cast<uint8_t *>(std::calloc(std::max<size_t>(size, 1), 1));
    if (!bytes)
        throw std::bad_alloc();
    return bytes;
}

} // namespace

void OverlayLayer::Free::operator()(uint8_t *p) const
{
    std::free(p);
}

OverlayLayer::OverlayLayer(unsigned width, unsigned height)
    : width_(width), height_(height), pixels_(zeroedBytes(size_t(width) * height * 4)), rowStart_(height + 1, 0)
{}

OverlayLayer::OverlayLayer(const OverlayLayer &other)
    : width_(other.width_), height_(other.height_), pixels_(zeroedBytes(other.bytes())), spans_(other.spans_),
      rowStart_(other.rowStart_), coveredPixels_(other.coveredPixels_)
{
    std::memcpy(pixels_.get(), other.pixels_.get(), bytes());
}

void OverlayLayer::clear()
{
    std::memset(pixels_.get(), 0, bytes());
    spans_.clear();
    std::fill(rowStart_.begin(), rowStart_.end(), 0);
    coveredPixels_ = 0;
}

void OverlayLayer::clearCovered()
{
    for (const Span &span : spans_)
        std::memset(data() + span.y * stride() + span.x0 * 4, 0, size_t(span.x1 - span.x0) * 4);
    spans_.clear();
    std::fill(rowStart_.begin(), rowStart_.end(), 0);
    coveredPixels_ = 0;
}

void OverlayLayer::fillRect(int x, int y, int width, int height, Rgba colour)
{
    const int x0 = std::max(x, 0), x1 = std::min(x + width, int(width_));
    const int y0 = std::max(y, 0), y1 = std::min(y + height, int(height_));
    // Premultiply with rounding so that a colour of 255 at alpha a stores exactly a.
    const auto premul = [&](uint8_t c) {
        return uint8_t((c * colour.a + 127) / 255);
    };
    const uint8_t px[4] = {premul(colour.r), premul(colour.g), premul(colour.b), colour.a};
    for (int row = y0; row < y1; ++row) {
        for (int col = x0; col < x1; ++col)
            std::memcpy(data() + row * stride() + col * 4, px, 4);
    }
}

void OverlayLayer::updateSpans()
{
    spans_.clear();
    coveredPixels_ = 0;
    for (unsigned y = 0; y < height_; ++y) {
        rowStart_[y] = spans_.size();
        const uint8_t *row = data() + y * stride();
        unsigned x = 0;
        while (x < width_) {
            // Most of a layer is transparent: test the alpha of four pixels at a time.
            static_assert(std::endian::native == std::endian::little, "alpha is the high byte of each 32-bit pixel");
            for (uint64_t a = 0, b = 0; x + 4 <= width_; x += 4) {
                std::memcpy(&a, row + x * 4, 8);
                std::memcpy(&b, row + x * 4 + 8, 8);
                if (((a | b) & 0xff000000ff000000ull) != 0)
                    break;
            }
            while (x < width_ && row[x * 4 + 3] == 0)
                ++x;
            const unsigned x0 = x;
            while (x < width_ && row[x * 4 + 3] != 0)
                ++x;
            if (x > x0) {
                spans_.push_back({y, x0, x});
                coveredPixels_ += x - x0;
            }
        }
    }
    rowStart_[height_] = spans_.size();
}

std::span<const Span> OverlayLayer::rowSpans(unsigned y) const
{
    return std::span<const Span>(spans_).subspan(rowStart_[y], rowStart_[y + 1] - rowStart_[y]);
}

} // namespace overlayd
