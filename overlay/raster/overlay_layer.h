// SPDX-License-Identifier: Apache-2.0
// OverlayLayer: the rendered overlay as premultiplied RGBA plus the spans it covers, drawn once per scene change.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "media/rgba.h"

namespace overlayd {

// Pixels [x0, x1) of row y all have coverage > 0; spans are maximal, so two spans of a row never touch.
struct Span {
    uint32_t y = 0, x0 = 0, x1 = 0;
};

class OverlayLayer
{
public:
    OverlayLayer(unsigned width, unsigned height);
    OverlayLayer(const OverlayLayer &other);
    OverlayLayer(OverlayLayer &&) noexcept = default;
    OverlayLayer &operator=(OverlayLayer &&) noexcept = default;

    unsigned width() const { return width_; }
    unsigned height() const { return height_; }
    // Rows of width * 4 bytes, R G B A, colour premultiplied by A (R, G, B <= A). A rasterizer may draw here
    // directly (OpenCV's anti-aliased drawing onto transparent black yields premultiplied colour).
    uint8_t *data() { return pixels_.get(); }
    const uint8_t *data() const { return pixels_.get(); }
    size_t stride() const { return size_t(width_) * 4; }
    size_t bytes() const { return stride() * height_; }
    const uint8_t *pixel(unsigned x, unsigned y) const { return data() + y * stride() + x * 4; }

    void clear();
    // Clears only the pixels of the spans found by the last updateSpans(): cheap when little is covered. Valid only
    // if nothing was drawn since.
    void clearCovered();
    // Replaces the pixels of a rectangle (clipped to the layer) with one colour.
    void fillRect(int x, int y, int width, int height, Rgba colour);

    // Call after drawing: rescans coverage so that the blend touches only covered pixels.
    void updateSpans();
    std::span<const Span> spans() const { return spans_; }
    std::span<const Span> rowSpans(unsigned y) const;
    size_t coveredPixels() const { return coveredPixels_; }

private:
    struct Free {
        void operator()(uint8_t *p) const;
    };

    unsigned width_, height_;
    // calloc'd: a large layer is fresh zero pages from the kernel, so only the pages drawn on become resident (a
    // zero-filled vector would write, and keep, every byte of a full-frame canvas).
    std::unique_ptr<uint8_t[], Free> pixels_;
    std::vector<Span> spans_;
    std::vector<uint32_t> rowStart_; // spans_ index of each row's first span, plus one past the end
    size_t coveredPixels_ = 0;
};

} // namespace overlayd
